// Error of a co-simulated signal against the reference, sampled on the same macro-step
// grid. Relative errors are normalised by the range (max - min) of the reference signal
// over the run, so that signals crossing zero get meaningful figures.
#pragma once

#include <span>
#include <string>

namespace mechsim::assess {

struct SignalError {
  double max_abs = 0.0;
  double rms_abs = 0.0;
  double max_rel = 0.0;    // max_abs / range
  double rms_rel = 0.0;
  double range = 0.0;      // of the reference
  double t_of_max = 0.0;   // time of the largest absolute error
  bool finite = true;      // false when the co-simulation produced NaN or Inf
};

// What relative errors are divided by: the range of the reference, or for a constant one
// its magnitude (at least 1), so that the figure stays defined. 1 for an empty series.
double relative_scale(std::span<const double> reference);

SignalError compare_signal(std::span<const double> t, std::span<const double> cosim, std::span<const double> reference);

// Where the worst error is a known artefact of the coupling, which one (docs/accuracy.md,
// "Reading the summary"):
//  - one_step_late: the co-simulation is the reference delayed by one macro step (what a
//    Jacobi edge does to the signal it carries, and to what is computed from it): shifted
//    back by one step, the worst difference is under a fifth of the error;
//  - jump: the reference jumps at the worst error (its step-to-step change there is over
//    ten times the median nonzero change, over 2 % of its range and at least half the
//    error), which a Jacobi
//    edge crosses one macro step late.
// With jumps, the largest error away from them (two steps either side left out) is what
// the coupling costs elsewhere.
struct ErrorCause {
  bool one_step_late = false;
  double max_abs_shifted = 0.0;   // max |cosim(t_k) - reference(t_k-1)|
  bool jump = false;
  double t_jump = 0.0;            // time of the jump at the worst error
  int jumps = 0;                  // jumps of the reference in the run
  double max_abs_away_from_jumps = 0.0;
};
ErrorCause classify_error(std::span<const double> t, std::span<const double> cosim, std::span<const double> reference);

}  // namespace mechsim::assess
