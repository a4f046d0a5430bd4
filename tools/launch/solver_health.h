// Integrator health of one node from the solver statistics it publishes on mechsim/status
// (issue 6 item 6; docs/accuracy.md "Stability and extreme cases"): a one-line summary and
// the stiffness hint. Pure functions, header-only (no I/O).
//
// The stiffness hint. An explicit method (arkode_erk), and CVODE's Adams method with its
// small stability region, must keep h |lambda_max| inside their stability region on a stiff
// block however smooth the solution is; BDF and DIRK step over decayed fast modes. The
// statistics cannot tell what BDF would do, so the hint looks at the symptom: a node on
// arkode_erk or cvode_adams that
//   - takes more than kHintStepsPerMacroStep (20) solver steps per macro step on average, and
//   - ends the run with a last step below H / kHintStepRatio (H / 20),
// is told that its block may be stiff and to try cvode_bdf or arkode_dirk. Twenty steps per
// exchange is far above what a smooth block needs at the usual tolerances (the NC and cam
// scenes take 1-10 per step with BDF; a restart each exchange already costs a few), and a
// last step 20x below H means the solver never got back to steps of the exchange's size.
// A block that is merely hard (events, discontinuities every step) can trip it too: it is a
// hint, printed next to the statistics, never an error.
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

inline double steps_per_macro_step(const NodeSolverFigures& f) {
  return f.macro_steps > 0 ? static_cast<double>(f.steps) / static_cast<double>(f.macro_steps) : 0.0;
}

inline std::optional<std::string> stiffness_hint(const NodeSolverFigures& f) {
  if (f.method != "arkode_erk" && f.method != "cvode_adams") return std::nullopt;
  const double per_step = steps_per_macro_step(f);
  if (!(per_step > kHintStepsPerMacroStep) || !(f.last_step > 0 && f.last_step < f.macro_step / kHintStepRatio))
    return std::nullopt;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%s took %.0f solver steps per macro step (last step %.3g s, H = %.3g s): the block may be stiff; "
                "try solver.method=cvode_bdf or arkode_dirk",
                f.method.c_str(), per_step, f.last_step, f.macro_step);
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
