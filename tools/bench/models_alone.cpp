#include "models_alone.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>

#include "json_io.h"
#include "provenance.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/stepped_run.h"

namespace mechsim::bench {

namespace {

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

long max_rss_kb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

}  // namespace

int run_models_alone(const std::string& scene_path, const ModelsAloneOptions& options, std::ostream& out) {
  std::unique_ptr<cosim::SteppedRun> run;
  try {
    // Building the plan (blocks, tables, steppers) is start-up, as a node's is before its
    // first step: outside the timing.
    run = std::make_unique<cosim::SteppedRun>(scene_path, options.set_overrides);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim bench --models-alone: %s\n", e.what());
    return 2;
  }
  const double cpu_before = cpu_seconds();
  const auto wall_before = std::chrono::steady_clock::now();
  try {
    run->advance(cosim::SteppedRun::kToTheEnd);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim bench --models-alone: %s\n", e.what());
    return 1;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_before).count();
  const double cpu = cpu_seconds() - cpu_before;
  if (run->diverged()) {
    std::fprintf(stderr, "mechsim bench --models-alone: diverged: %s\n", run->diverged()->c_str());
    return 1;
  }
  const auto steps = run->steps();
  const std::size_t participants = run->plan().nodes().size();
  const double steps_per_s = static_cast<double>(steps) / wall;
  const double cpu_us_per_step = 1e6 * cpu / static_cast<double>(steps);
  char line[256];
  std::snprintf(line, sizeof line,
                "models alone (%zu participants, one thread, no transport): %llu steps in %.4f s wall, %.4f s CPU: "
                "%.0f steps/s, %.3f us CPU/step, max RSS %ld kB\n",
                participants, static_cast<unsigned long long>(steps), wall, cpu, steps_per_s, cpu_us_per_step, max_rss_kb());
  out << line;
  if (!options.json_path.empty()) {
    nlohmann::json doc = {{"schema_version", tools::schema_version},
                          {"provenance", tools::provenance(scene_path)},
                          {"overrides", options.set_overrides},
                          {"master", "models_alone"},
                          {"participants", participants},
                          {"steps", steps},
                          {"wall_s", wall},
                          {"cpu_s", cpu},
                          {"steps_per_s", steps_per_s},
                          {"cpu_us_per_step", cpu_us_per_step},
                          {"max_rss_kb", max_rss_kb()}};
    tools::write_json_file(options.json_path, doc);
  }
  return 0;
}

}  // namespace mechsim::bench
