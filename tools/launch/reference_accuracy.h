// The reference's accuracy check (cosim::estimate_reference_error) as it appears in the
// JSON of `mechsim reference`, in the `reference` block of a launch summary and in the
// bench: per compared signal, the difference between the reference and its re-run at a
// 100x tighter tolerance, absolute and relative to the reference signal's range.
#pragma once

#include <nlohmann/json.hpp>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"

namespace mechsim::launch {

// {"rtol_check", "atol_check", "wall_time_s", "signals": {name: {max_abs_difference,
// rms_abs_difference, max_rel_difference, rms_rel_difference}}}
nlohmann::json reference_accuracy_json(const config::Scene& scene, const cosim::ReferenceRun& ref,
                                       const cosim::ReferenceAccuracy& accuracy);

// One line per compared signal.
void print_reference_accuracy(const nlohmann::json& accuracy);

}  // namespace mechsim::launch
