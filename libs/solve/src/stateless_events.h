// Zero crossings of a block without continuous states (a model-exchange FMU with time
// events only, e.g. a staircase or a sampled controller): no solver is running whose root
// finding could locate them, and the event functions depend on time and the inputs alone,
// so the first crossing in an interval is found by bisection on time. docs/fmi.md, "Model
// exchange without states".
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "mechsim/models/block.h"

namespace mechsim::solve::detail {

// The first instant in (t, target] at which an event function crosses zero in its
// direction, to `resolution` [s] (the far side of the crossing: g has crossed there), with
// `crossed[i]` = +1 (rising), -1 (falling) or 0; nullopt when none crosses. A crossing
// within `resolution` after `target` counts as one at `target` (a time event computed a
// few ulps after the macro instant it is meant for). `g_at(t, g)` evaluates every function at t.
std::optional<double> first_stateless_crossing(const std::function<void(double, std::span<double>)>& g_at,
                                               std::span<const models::Crossing> directions, double t, double target,
                                               double resolution, std::span<int> crossed);

}  // namespace mechsim::solve::detail
