// The comparison of a finished run with the monolithic reference (signal errors, their
// causes, the reference's own accuracy, the report's figures) and the files it leaves in
// the run folder: signals.csv, signals.png and the lateness plots of a real-time run.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::launch {

// Runs the reference on the instants the nodes logged and adds "signals", "report",
// "reference", "files" (and an adaptive run's suggested scales) to `summary`.
void compare_with_reference(const config::Scene& scene, const cosim::ScenePlan& plan, const std::string& run_dir, bool plots,
                            nlohmann::json& summary);
// A real-time run's lateness plots, listed under summary["files"]["lateness_png"].
void plot_lateness(const config::Scene& scene, const std::string& run_dir, nlohmann::json& summary);

}  // namespace mechsim::launch
