#include "cam_lift_off_launch.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "node_processes.h"
#include "install_paths.h"

namespace mechsim::tools::cam_design {

namespace fs = std::filesystem;

namespace {

// The launcher's last words ("mechsim: run failed: ...") for the error message.
std::string last_lines(const std::string& path, std::size_t n) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  std::string out;
  for (std::size_t i = lines.size() > n ? lines.size() - n : 0; i < lines.size(); ++i) out += "\n  " + lines[i];
  return out;
}

}  // namespace

LiftOffRun launch_lift_off_run(const config::Scene& scene, const RollerCase& roller, const LiftOffLaunchOptions& options,
                               double speed_rad_s, double revolutions, int index) {
  // Refuses an unsuitable scene before any process starts.
  const std::vector<std::string> own = lift_off_run_overrides(scene, roller, speed_rad_s, revolutions);
  char tag[32];
  std::snprintf(tag, sizeof tag, "run-%02d", index);
  const std::string log = (fs::path(options.sweep_dir) / (std::string(tag) + ".log")).string();
  const std::string summary_path = (fs::path(options.sweep_dir) / (std::string(tag) + ".json")).string();
  fs::create_directories(options.sweep_dir);

  std::vector<std::string> args{"launch", options.scene_path, "--runs-dir", options.sweep_dir, "--json", summary_path,
                                "--no-plot", "--no-progress"};
  for (const auto* list : {&options.overrides, &own})
    for (const auto& o : *list) {
      args.push_back("--set");
      args.push_back(o);
    }
  const std::string exe = options.mechsim_executable.empty()
                              ? (fs::path(hostrun::executable_dir()) / "mechsim").string()
                              : options.mechsim_executable;

  const auto started = std::chrono::steady_clock::now();
  // The launcher watches its nodes (hangs, deaths) and always ends; this process only waits.
  // A child dies with this process (NodeProcesses sets PR_SET_PDEATHSIG), its nodes with it.
  hostrun::NodeProcesses child;
  child.start("launch", exe, args, log);
  while (!child.all_exited()) {
    child.poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const hostrun::NodeProcess& p = child.processes().front();
  char speed[64];
  std::snprintf(speed, sizeof speed, "%.2f rpm", speed_rad_s * 60.0 / (2.0 * std::numbers::pi));
  if (p.signalled || p.exit_code != 0)
    throw std::runtime_error("the run at " + std::string(speed) + " failed (`mechsim launch`, " + p.describe_exit() +
                             "); its output, " + log + ":" + last_lines(log, 4));
  std::ifstream in(summary_path);
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (summary.is_discarded()) throw std::runtime_error(summary_path + ": the run summary is not JSON");
  try {
    return lift_off_run_from_summary(summary, roller.follower_participant, speed_rad_s, wall);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("the run at " + std::string(speed) + ": " + e.what() + " (" + summary_path + ")");
  }
}

}  // namespace mechsim::tools::cam_design
