// One run of the lift-off sweep (cam_lift_off_sweep.h) as a real distributed run: `mechsim
// launch` of the scene at one cam speed, in a child process with its own log, run folder and
// summary, exactly as a user would start it. The launcher gives it a free DDS domain, starts
// the node processes, and lists the follower's lift-off events in the summary.
#pragma once

#include <string>
#include <vector>

#include "cam_design_case.h"
#include "cam_lift_off_sweep.h"
#include "mechsim/config/scene.h"

namespace mechsim::tools::cam_design {

struct LiftOffLaunchOptions {
  std::string scene_path;
  std::vector<std::string> overrides;  // the user's ("dotted.key=value"), before each run's own
  std::string sweep_dir;               // run folders, summaries (run-NN.json) and logs (run-NN.log)
  std::string mechsim_executable;      // "" = the `mechsim` next to the running executable
};

// Runs the scene (`scene`: loaded from options.scene_path with options.overrides) at
// `speed_rad_s` for `revolutions` revolutions; `index` numbers its files. Throws
// std::runtime_error naming the log when the run fails, config::ConfigError when the scene
// cannot be swept (see lift_off_run_overrides).
LiftOffRun launch_lift_off_run(const config::Scene& scene, const RollerCase& roller, const LiftOffLaunchOptions& options,
                               double speed_rad_s, double revolutions, int index);

}  // namespace mechsim::tools::cam_design
