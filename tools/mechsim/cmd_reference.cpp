#include <cstdio>

#include "assessment_json.h"
#include "commands.h"
#include "csv.h"
#include "json_io.h"
#include "mechsim/assess/report_figures.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/scene_plan.h"
#include "provenance.h"
#include "run_report.h"

namespace mechsim::tools {

void add_reference_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("reference",
                                 "Run a scene monolithically: all blocks in one ODE at tight tolerance, in this process");
  auto args = std::make_shared<SceneArgs>();
  auto json_path = std::make_shared<std::string>();
  auto csv_path = std::make_shared<std::string>();
  auto rtol = std::make_shared<double>(1e-10);
  add_scene_args(cmd, *args);
  cmd->add_option("--json", *json_path, "write the reference summary (JSON) to this file");
  cmd->add_option("--csv", *csv_path, "write every output at every macro step (CSV) to this file");
  cmd->add_option("--rtol", *rtol, "relative tolerance of the monolithic integration (atol = rtol / 100); the run is "
                  "repeated at a 100x tighter tolerance to estimate the reference's own error")
      ->capture_default_str();
  cmd->callback([=, &exit_code] {
    config::Scene scene;
    try {
      scene = config::load_scene(args->scene, args->overrides());
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
      return;
    }
    try {
      cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
      // An adaptive scene has no grid before a run: sampled every `max` (and at the end).
      std::vector<double> instants;
      if (const auto& a = scene.time.adaptive) {
        for (double t = scene.time.start; t < scene.time.end; t = scene.time.start + static_cast<double>(instants.size()) * a->max)
          instants.push_back(t);
        instants.push_back(scene.time.end);
      }
      cosim::ReferenceRun ref = instants.empty() ? cosim::run_reference(plan, *rtol, *rtol * 1e-2)
                                                 : cosim::run_reference_at(plan, instants, *rtol, *rtol * 1e-2);
      const cosim::ReferenceAccuracy accuracy = cosim::estimate_reference_error(scene, ref);
      const auto& t = ref.log.data[0];
      auto series = [&](const config::SignalRef& r) -> std::span<const double> {
        int c = ref.log.column(r.full_name());
        return c < 0 ? std::span<const double>{} : std::span<const double>(ref.log.data[c]);
      };
      nlohmann::json summary{{"schema_version", schema_version},
                             {"provenance", provenance(scene.file)},
                             {"scene", scene.name},
                             {"steps", static_cast<long>(ref.log.rows()) - 1},
                             {"macro_step_s", scene.time.step},
                             {"simulated_time_s", scene.time.end - scene.time.start},
                             {"rtol", ref.rtol},
                             {"wall_time_s", ref.wall_time_s},
                             {"solver", launch::solver_stats_json(ref.stats)},
                             {"accuracy", reference_accuracy_json(scene, ref, accuracy)},
                             {"report", report_figures_json(assess::report_figures(scene, t, series))}};
      std::printf("reference of '%s': %ld samples, rtol %g, %ld solver steps, %.3f s wall\n", scene.name.c_str(),
                  static_cast<long>(ref.log.rows()), ref.rtol, ref.stats.steps, ref.wall_time_s);
      print_reference_accuracy(summary["accuracy"]);
      print_figures(summary["report"]);
      if (!json_path->empty()) write_json_file(*json_path, summary);
      if (!csv_path->empty()) write_csv(*csv_path, ref.log.columns, ref.log.data);
      exit_code = 0;
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim reference: %s\n", e.what());
      exit_code = 1;
    }
  });
}

std::string version_string() {
  return std::string("mechsim ") + MECHSIM_VERSION + " (commit " + MECHSIM_GIT_COMMIT + ")";
}

}  // namespace mechsim::tools
