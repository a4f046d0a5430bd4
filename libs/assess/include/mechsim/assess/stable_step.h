// In-process runs of a scene stepped by hand with the product's NodeSteppers (the code of
// every node process, without transport: the numbers of a DDS run), for stability
// questions: is the coupled run stable at macro step H? Used by `mechsim bench --stability`
// (tools/bench/stability.cpp: bisection, linear analysis of the macro-step map) and by the
// launcher to name a stable step when a run diverges.
//
// A trial is unstable when the divergence guard of a node fires (non-finite output, or an
// oscillation growing window after window: libs/cosim/src/divergence_guard.cpp), when a
// node's solver fails, or when the coupling element's spring energy T^2 / (2 C) over the
// last tenth of the run exceeds 4x its maximum before and 1e-6 of its peak (a stable loop's
// spring energy decays after the transient; an unstable mode's grows and peaks at the end).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/stepped_run.h"

namespace mechsim::assess {

// Each trial lasts the scene's duration or this many steps, whichever is longer (the
// guard's slow criterion needs 1500 steps to see a mode growing by a few per mille per step).
inline constexpr long kMinSteps = 2000;

struct StepTrial {
  bool stable = true;
  std::string why;  // the guard's reason, the solver failure or the energy growth
};

// The overrides that put the scene at macro step h: the step, an end at a whole number of
// steps (at least kMinSteps), and every participant sampled at the scene's own macro step
// sampled at h too (a sampled amplifier, identical in the reference).
std::vector<std::string> at_macro_step(const config::Scene& base, double h, std::vector<std::string> overrides);

// One trial at macro step h; energy of the coupling element between a and b if stiffness > 0.
// Throws config::ConfigError for a scene the overrides make invalid.
StepTrial try_macro_step(const std::string& path, const config::Scene& base, const std::vector<std::string>& overrides,
                         double h, const std::string& a = "", const std::string& b = "", double stiffness = 0.0);

// The largest stable step found by halving h up to `halvings` times (nullopt: none), with
// the energy of every coupling element of the scene watched (the first one's).
std::optional<double> find_stable_step_below(const std::string& path, const std::vector<std::string>& overrides, double h,
                                             int halvings = 6);

}  // namespace mechsim::assess
