// The real-time side of a run's summary: lateness, deadlines and period jitter per node
// (from <node>.realtime.json, written by paced nodes), the operating-system settings each
// node applied (<node>.process.json), the lateness histogram PNG per node, and the
// launcher's pre-flight check of the rights those settings need.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/step_grid.h"

namespace mechsim::launch {

// Empty when this (the launcher's) process may apply every participant's realtime process
// settings — the node processes inherit its credentials and limits; otherwise the refusals,
// one line each.
std::vector<std::string> realtime_rights_problems(const config::Scene& scene);

// {"rtf_requested", ..., "missed_deadlines", "lateness_p99_s", "lateness_max_s",
//  "period_jitter_std_s", "period_jitter_max_s", "nodes": {node: figures}} of a paced run.
nlohmann::json realtime_summary(const config::Scene& scene, const cosim::StepGrid& grid, const std::vector<std::string>& nodes,
                                const std::string& run_dir,
                                const std::vector<std::string>& warnings);

// {node: {"policy", "priority", "memory_locked", "cpus"}} of the nodes that applied settings.
nlohmann::json process_settings_summary(const std::vector<std::string>& nodes, const std::string& run_dir);

// <run>/<node>.lateness.png per paced node: the lateness histogram (log count over
// lateness), with p99, the maximum and the one-step deadline marked. Returns the files
// written; explains a missing plot through *why.
std::vector<std::string> write_lateness_plots(const nlohmann::json& realtime, double step_wall_s, const std::string& run_dir,
                                              std::string* why);

// The summary lines of the two sections above (printed after the signals).
void print_realtime_summary(const nlohmann::json& summary);

}  // namespace mechsim::launch
