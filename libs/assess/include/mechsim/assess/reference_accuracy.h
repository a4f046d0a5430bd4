// The reference's accuracy check (cosim::estimate_reference_error) per compared signal: the
// difference between the reference and its re-run at a tighter tolerance, absolute and
// relative to the reference signal's range (as the co-simulation's errors: signal_compare.h).
// Shown by `mechsim reference`, in the `reference` block of a launch summary and in the bench.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"

namespace mechsim::assess {

struct SignalAccuracy {
  std::string signal;  // "participant.output"
  double max_abs = 0.0, rms_abs = 0.0;  // |reference - tighter run|
  double max_rel = 0.0, rms_rel = 0.0;  // divided by relative_scale(reference)
};

// One entry per compared signal of the scene that the reference logged, in the scene's order.
std::vector<SignalAccuracy> reference_signal_accuracy(const config::Scene& scene, const cosim::ReferenceRun& ref,
                                                      const cosim::ReferenceAccuracy& accuracy);

}  // namespace mechsim::assess
