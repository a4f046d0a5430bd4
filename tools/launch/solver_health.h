// Integrator health of one node from the solver statistics it publishes on mechsim/status
// (issue 6 item 6; docs/accuracy.md "Stability and extreme cases"): a one-line summary and
// the stiffness hint. Pure functions, header-only (no I/O).
//
// The stiffness hint. An explicit method (arkode_erk), and CVODE's Adams method with its
// small stability region, must keep h |lambda_max| inside their stability region on a stiff
// block however smooth the solution is; BDF and DIRK step over decayed fast modes. The
// statistics cannot tell what BDF would do, so the hint looks at the symptoms of a solver
// held at its stability boundary. A node on arkode_erk or cvode_adams that
//   - takes more than kHintStepsPerMacroStep (20) solver steps per macro step on average,
//   - ends the run with a last step below H / kHintStepRatio (H / 20), and
//   - has error-test failures on at least kHintFailureRatio (10 %) of its steps
// is told that its block may be stiff and to try cvode_bdf or arkode_dirk. The third
// criterion separates "held by stability" from "held by accuracy": a step beyond the
// stability boundary amplifies the error estimate and is rejected, so the controller keeps
// bouncing off the boundary (15-17 % rejected steps for arkode_erk on the 10^4 x stiffer
// follower, where BDF ends the run with 2 ms steps), while a solver that resolves a fast
// transient at every exchange takes small steps with few rejections (0.3 % for arkode_erk
// on nc_small_inductance, where BDF takes even more steps). The thresholds were set on
// these two scenes (docs/accuracy.md); it is a hint printed next to the statistics, never
// an error.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

namespace mechsim::launch {

struct NodeSolverFigures {
  std::string method;          // cvode_bdf | cvode_adams | arkode_erk | arkode_dirk
  long long steps = 0, rhs_evals = 0, error_test_failures = 0, nonlinear_failures = 0, roots_found = 0;
  double last_step = 0.0;      // s
  long last_order = 0;
  long macro_steps = 0;        // of the run (or the steps the node completed)
  double macro_step = 0.0;     // H, s
};

inline constexpr double kHintStepsPerMacroStep = 20.0;
inline constexpr double kHintStepRatio = 20.0;
inline constexpr double kHintFailureRatio = 0.10;

inline double steps_per_macro_step(const NodeSolverFigures& f) {
  return f.macro_steps > 0 ? static_cast<double>(f.steps) / static_cast<double>(f.macro_steps) : 0.0;
}

inline std::optional<std::string> stiffness_hint(const NodeSolverFigures& f) {
  if (f.method != "arkode_erk" && f.method != "cvode_adams") return std::nullopt;
  const double per_step = steps_per_macro_step(f);
  if (!(per_step > kHintStepsPerMacroStep) || !(f.last_step > 0 && f.last_step < f.macro_step / kHintStepRatio))
    return std::nullopt;
  const double rejected = f.steps > 0 ? static_cast<double>(f.error_test_failures) / static_cast<double>(f.steps) : 0.0;
  if (!(rejected >= kHintFailureRatio)) return std::nullopt;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%s took %.0f solver steps per macro step (last step %.3g s, H = %.3g s, %.0f %% of steps rejected): "
                "the block may be stiff; try solver.method=cvode_bdf or arkode_dirk",
                f.method.c_str(), per_step, f.last_step, f.macro_step, 100 * rejected);
  return std::string(buf);
}

// "cvode_bdf: 8483 steps (5.7 per macro step), 14483 rhs, 389 error-test / 0 convergence
// failures, 6 roots, last step 5.37e-07 s, order 1"
inline std::string solver_line(const NodeSolverFigures& f) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%s: %lld steps (%.1f per macro step), %lld rhs, %lld error-test / %lld convergence failures, %lld roots, "
                "last step %.3g s, order %ld",
                f.method.c_str(), f.steps, steps_per_macro_step(f), f.rhs_evals, f.error_test_failures, f.nonlinear_failures,
                f.roots_found, f.last_step, f.last_order);
  return buf;
}

}  // namespace mechsim::launch
