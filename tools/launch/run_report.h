// Pieces of a run summary shared by `launch` and `reference`: the scene's `report:`
// extrema and the solver statistics, as JSON.
#pragma once

#include <functional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/solve/solver_options.h"

namespace mechsim::launch {

// Looks up a compared signal's time series by "participant.output".
using SeriesLookup = std::function<std::span<const double>(const config::SignalRef&)>;

nlohmann::json report_extrema(const config::Scene& scene, std::span<const double> t, const SeriesLookup& series);
nlohmann::json solver_stats_json(const solve::SolverStats& s);

}  // namespace mechsim::launch
