// The error assessment's results (libs/assess) as they appear in the JSON of `mechsim
// reference`, of a launch summary and of the bench, and on the console.
#pragma once

#include <span>

#include <nlohmann/json.hpp>

#include "mechsim/assess/reference_accuracy.h"
#include "mechsim/assess/report_figures.h"
#include "mechsim/cosim/composer.h"

namespace mechsim::tools {

// {"method", "rtol_check", "atol_check", "wall_time_s", "solver_steps", "signals": {name:
// {max_abs_difference, rms_abs_difference, max_rel_difference, rms_rel_difference}}}
nlohmann::json reference_accuracy_json(const cosim::ReferenceAccuracy& accuracy, std::span<const assess::SignalAccuracy> signals);
// The same, computed for the scene's compared signals.
nlohmann::json reference_accuracy_json(const config::Scene& scene, const cosim::ReferenceRun& ref,
                                       const cosim::ReferenceAccuracy& accuracy);
// One line per compared signal.
void print_reference_accuracy(const nlohmann::json& accuracy);

// One JSON object per figure: {"stat", "signal", the figures, and with a reference
// "reference" (its figures) and "relative_difference"}.
nlohmann::json report_figures_json(std::span<const assess::ReportFigure> figures);
// Prints the figures, one line each.
void print_figures(const nlohmann::json& figures);

}  // namespace mechsim::tools
