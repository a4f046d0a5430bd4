#include "scene_run.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "mechsim/cosim/scene_plan.h"

namespace mechsim::sweep {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Run ids of this process: a node's log carries its run's id.
std::uint64_t next_run_id() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

SceneRun run_scene(const std::string& scene_path, const std::vector<std::string>& overrides, const std::string& run_dir) {
  SceneRun out;
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<cosim::ScenePlan> plan;
  try {
    out.scene = std::make_unique<config::Scene>(config::load_scene(scene_path, overrides));
    plan = std::make_unique<cosim::ScenePlan>(cosim::ScenePlan::build(*out.scene));
  } catch (const std::exception& e) {
    out.scene.reset();
    out.reason = e.what();
    out.wall_time_s = seconds_since(t0);
    return out;
  }
  std::filesystem::create_directories(run_dir);
  cosim::InprocRunOptions io;
  io.run_dir = run_dir;
  io.run_id = next_run_id();
  const auto t_run = std::chrono::steady_clock::now();
  try {
    out.inproc = cosim::run_inproc(*out.scene, io);
  } catch (const std::exception& e) {
    out.reason = e.what();
    out.wall_time_s = seconds_since(t0);
    return out;
  }
  out.run_wall_time_s = seconds_since(t_run);
  if (!out.inproc.ok) {
    out.outcome = out.inproc.diverged ? "diverged" : "failed";
    out.reason = out.inproc.reason;
    out.steps = static_cast<long>(out.inproc.failed_step);
    out.wall_time_s = seconds_since(t0);
    return out;
  }
  try {
    out.comparison = assess::compare_with_reference(*out.scene, *plan, run_dir);
    out.outcome = "ok";
    out.steps = out.comparison->t.empty() ? 0 : static_cast<long>(out.comparison->t.size()) - 1;
    // A run that went non-finite without tripping a node's guard has no error to report.
    for (const auto& s : out.comparison->signals)
      if (!s.error.finite) {
        out.outcome = "diverged";
        out.reason = s.signal.full_name() + ": the co-simulation is not finite";
        break;
      }
  } catch (const std::exception& e) {
    out.outcome = "failed";
    out.reason = std::string("comparison with the reference: ") + e.what();
  }
  out.wall_time_s = seconds_since(t0);
  return out;
}

}  // namespace mechsim::sweep
