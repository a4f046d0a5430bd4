// Pieces of a run summary shared by `launch` and `reference`: the scene's `report:`
// figures (extrema, step-response figures, time in a state) and solver statistics, as JSON.
#pragma once

#include <functional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/solve/solver_options.h"

namespace mechsim::launch {

// Looks up a signal's time series by "participant.output" (empty span when unknown).
using SeriesLookup = std::function<std::span<const double>(const config::SignalRef&)>;

// Step-response figures of y(t) towards `target` from its initial value.
struct StepResponse {
  double rise_time = 0.0;      // s, 10 % -> 90 % of the step
  double overshoot = 0.0;      // fraction of the step beyond the target (0 if none)
  double settling_time = 0.0;  // s from t0 until y stays within band * step of the target
  double final_value = 0.0;
  bool settled = false;        // y ended inside the band
};
StepResponse step_response(std::span<const double> t, std::span<const double> y, double target, double band);

// One JSON object per `report:` entry. With `reference` given, each figure also carries the
// reference's value and the relative difference.
nlohmann::json report_figures(const config::Scene& scene, std::span<const double> t, const SeriesLookup& series,
                              const SeriesLookup* reference = nullptr);
nlohmann::json solver_stats_json(const solve::SolverStats& s);

// The steps an adaptive run took (time.step: adaptive): {tolerance, min_s, max_s, steps,
// shortest_s, longest_s, median_s, events}; shortest/longest null without instants.
nlohmann::json adaptive_step_summary(const config::AdaptiveStepSpec& spec, std::span<const double> instants);

// Prints the figures, one line each.
void print_figures(const nlohmann::json& figures);

}  // namespace mechsim::launch
