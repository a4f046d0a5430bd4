// The files a run's comparison with the monolithic reference (assess::compare_with_reference,
// libs/assess) leaves in the run folder and its summary: signals.csv, signals.png and the
// lateness plots of a real-time run.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "mechsim/assess/reference_comparison.h"
#include "mechsim/config/scene.h"

namespace mechsim::launch {

// Adds "signals", "report", "reference", "files" (and an adaptive run's suggested scales) to
// `summary` and writes signals.csv (and with `plots` signals.png) into run_dir.
void write_comparison(const config::Scene& scene, const assess::ReferenceComparison& comparison, const std::string& run_dir,
                      bool plots, nlohmann::json& summary);
// A real-time run's lateness plots, listed under summary["files"]["lateness_png"].
void plot_lateness(const config::Scene& scene, const std::string& run_dir, nlohmann::json& summary);

}  // namespace mechsim::launch
