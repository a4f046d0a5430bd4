// What a node process and a process group both do before their nodes run (node_main.cpp).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/node_command_line.h"
#include "mechsim/cosim/node_runner.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::nodes {

// The node's own plan (its own blocks); a replayed node publishes `replay`'s table instead.
std::unique_ptr<cosim::ScenePlan> node_plan(const config::Scene& scene, const std::string& node_name, const std::string& replay);
// The participant's real-time process settings, in real-time mode only, before any DDS
// participant exists; their report goes to <run_dir>/<name>.process.json for each name.
void apply_realtime(const config::Scene& scene, const config::ParticipantSpec& spec, const std::string& run_dir,
                    const std::vector<std::string>& names);
// The run options the command line sets (run folder, run id, domain, control writer, resume).
cosim::NodeRunOptions run_options(const cosim::NodeCommandLine& command_line);
// The participant's test seams (`participants.<p>.testing`, restart and placement tests).
void apply_testing_seams(const config::ParticipantSpec& spec, cosim::NodeRunOptions& options);
// SIGINT and SIGTERM set stop_signalled().
void stop_on_signals();
const std::atomic<bool>& stop_signalled();

}  // namespace mechsim::nodes
