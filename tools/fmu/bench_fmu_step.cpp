// Per-step cost of an FMU participant against the same law as a native participant
// (issue 27 item 7; run by tools/bench-fmu.sh, docs/fmi.md "Cost of an FMU participant").
//
// The scene is config/scenes/nc_slide_loop.yaml; its servo amplifier is played in turn by
// each variant: the native block, and each FMU given (`--fmu NAME=FILE:INTERFACE`) through
// `participants.servo.fmu:` (the plan builds the FMU's block in its place). Two figures,
// measured interleaved (variant after variant, round after round) so that a busy machine
// loads them alike:
//   block  the servo participant's own work per macro step, as its node does it
//          (NodeStepper::step: restart, integrate the step with the inputs held, outputs),
//          over the same input signals for every variant;
//   scene  CPU time per macro step of the whole scene run in process (run_inproc: three
//          node threads over the in-process transport), which also holds the other nodes.
// Times are CPU time (the thread's for block, the process's for scene), which a busy machine
// disturbs less than wall time. Prints per variant the median over the rounds and the ratio
// to native (median, min, max over the rounds).
#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/solve/block_integrator.h"

namespace fs = std::filesystem;
using namespace mechsim;

namespace {

struct Variant {
  std::string name;
  std::string fmu_line;  // "" for the native amplifier
  std::string scene_file;
  std::vector<double> block_us, scene_us;
};

double cpu_seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The scene with `fmu_line` under the servo participant, written to `path`.
void write_scene(const std::string& scene, const std::string& fmu_line, const std::string& path) {
  std::string text = read_text(scene);
  const std::string anchor = "    type: servo_amplifier\n";
  const auto at = text.find(anchor);
  if (at == std::string::npos) throw std::runtime_error(scene + ": no servo_amplifier participant line");
  if (!fmu_line.empty()) text.insert(at + anchor.size(), "    " + fmu_line + "\n");
  std::ofstream(path) << text;
}

// Microseconds per macro step of the servo's block, stepped as a node steps it.
double block_cost(const config::Scene& scene, int steps) {
  cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  cosim::PlannedNode& node = plan.node("servo");
  models::Block& block = *node.block;
  const double h = scene.time.step;
  std::vector<double> x(block.num_states()), u = block.default_inputs(), y(block.num_outputs());
  block.initial_state(0.0, x);
  solve::BlockIntegrator integrator(block, cosim::solver_options(node.spec->solver), 0.0, x);
  const int tacho = block.input_index("tacho_voltage"), angle = block.input_index("spindle_angle");
  // A spindle turning into the 0.1 mm step and a tacho voltage with a 200 Hz ripple: the
  // loop's own signals in size, the same for every variant.
  const auto inputs_at = [&](double t, std::span<double> v) {
    if (tacho >= 0) v[tacho] = 2.0 * std::sin(2 * std::numbers::pi * 200.0 * t);
    if (angle >= 0) v[angle] = 0.12 * (1 - std::exp(-t / 5e-3));
  };
  if (block.sample_time() > 0)
    integrator.advance_to(0.0, [&](double, std::span<double> v) { std::copy(u.begin(), u.end(), v.begin()); });
  const double start = cpu_seconds(CLOCK_THREAD_CPUTIME_ID);
  for (int k = 0; k < steps; ++k) {
    const double t = k * h, t_next = (k + 1) * h;
    inputs_at(t, u);
    integrator.mark_discontinuity();
    integrator.advance_to(t_next, [&](double, std::span<double> v) { std::copy(u.begin(), u.end(), v.begin()); });
    inputs_at(t_next, u);
    block.calc_outputs(t_next, integrator.state(), u, y);
  }
  return (cpu_seconds(CLOCK_THREAD_CPUTIME_ID) - start) * 1e6 / steps;
}

double scene_cost(const config::Scene& scene, const std::string& run_dir) {
  fs::create_directories(run_dir);
  cosim::InprocRunOptions options;
  options.run_dir = run_dir;
  // CPU time of the whole process over the run: the plan building and FMU loading of
  // run_inproc are in it too, the same for every variant but for the FMU's unpacking.
  const double start = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID);
  const auto result = cosim::run_inproc(scene, options);
  const double spent = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID) - start;
  if (!result.ok) throw std::runtime_error("run failed: " + result.reason);
  return spent * 1e6 / static_cast<double>(scene.time.steps());
}

void usage() {
  std::fputs(
      "usage: mechsim-bench-fmu --scene NC_SCENE [--rounds N] [--end T_S] --fmu NAME=FMU_LINE ...\n"
      "  Per-step cost of the servo amplifier played by each FMU against the native amplifier, interleaved.\n"
      "  FMU_LINE is the participant's fmu: entry, e.g. '{file: s.fmu, interface: co-simulation}'.\n",
      stderr);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path;
  int rounds = 5;
  std::string end = "0.05";
  std::vector<Variant> variants{{"native", "", "", {}, {}}};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else if (a == "--scene") {
      scene_path = value();
    } else if (a == "--rounds") {
      rounds = std::stoi(value());
    } else if (a == "--end") {
      end = value();
    } else if (a == "--fmu") {
      const std::string v = value();
      const auto eq = v.find('=');
      if (eq == std::string::npos) throw std::runtime_error("--fmu expects NAME=FMU_LINE");
      variants.push_back({v.substr(0, eq), "fmu: " + v.substr(eq + 1), "", {}, {}});
    } else {
      usage();
      return 2;
    }
  }
  if (scene_path.empty()) {
    usage();
    return 2;
  }
  std::string pattern = (fs::temp_directory_path() / "mechsim-bench-fmu-XXXXXX").string();
  const fs::path tmp = mkdtemp(pattern.data());
  try {
    std::vector<config::Scene> scenes;
    for (auto& v : variants) {
      v.scene_file = (tmp / (v.name + ".yaml")).string();
      write_scene(scene_path, v.fmu_line, v.scene_file);
      // A loaded machine can starve a node thread for seconds: not a partition here.
      scenes.push_back(config::load_scene(v.scene_file, {"time.end=" + end + " s", "faults.partition_grace=60 s"}));
    }
    const int steps = static_cast<int>(scenes[0].time.steps());
    std::printf("scene %s, %d macro steps of %g us, %d rounds interleaved\n", scene_path.c_str(), steps,
                scenes[0].time.step * 1e6, rounds);
    for (int r = 0; r < rounds; ++r)
      for (std::size_t i = 0; i < variants.size(); ++i) {
        variants[i].block_us.push_back(block_cost(scenes[i], steps));
        variants[i].scene_us.push_back(scene_cost(scenes[i], (tmp / ("run" + std::to_string(r) + variants[i].name)).string()));
      }
    const auto ratios = [&](const Variant& v, auto member) {
      std::vector<double> q;
      for (int r = 0; r < rounds; ++r) q.push_back((v.*member)[r] / (variants[0].*member)[r]);
      std::sort(q.begin(), q.end());
      return q;
    };
    std::printf("%-22s %14s %22s %14s %22s\n", "servo played by", "block cpu us/step", "ratio med [min, max]",
                "scene cpu us/step", "ratio med [min, max]");
    for (const auto& v : variants) {
      const auto qb = ratios(v, &Variant::block_us);
      const auto qs = ratios(v, &Variant::scene_us);
      std::printf("%-22s %14.3f %8.2f [%5.2f, %5.2f] %14.3f %8.2f [%5.2f, %5.2f]\n", v.name.c_str(), median(v.block_us),
                  median(qb), qb.front(), qb.back(), median(v.scene_us), median(qs), qs.front(), qs.back());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim-bench-fmu: %s\n", e.what());
    fs::remove_all(tmp);
    return 1;
  }
  fs::remove_all(tmp);
  return 0;
}
