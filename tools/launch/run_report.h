// Pieces of a run summary shared by `launch` and `reference`: solver statistics and the
// steps of an adaptive run, as JSON. (The report's figures: libs/assess report_figures.h,
// written by tools/assessment.)
#pragma once

#include <span>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/solve/solver_options.h"

namespace mechsim::launch {

nlohmann::json solver_stats_json(const solve::SolverStats& s);

// The steps an adaptive run took (time.step: adaptive): {tolerance, min_s, max_s, steps,
// shortest_s, longest_s, median_s, events}; shortest/longest null without instants.
nlohmann::json adaptive_step_summary(const config::AdaptiveStepSpec& spec, std::span<const double> instants);

}  // namespace mechsim::launch
