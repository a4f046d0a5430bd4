// Error of a co-simulated signal against the reference, sampled on the same macro-step
// grid. Relative errors are normalised by the range (max - min) of the reference signal
// over the run, so that signals crossing zero get meaningful figures.
#pragma once

#include <span>
#include <string>

namespace mechsim::launch {

struct SignalError {
  double max_abs = 0.0;
  double rms_abs = 0.0;
  double max_rel = 0.0;    // max_abs / range
  double rms_rel = 0.0;
  double range = 0.0;      // of the reference
  double t_of_max = 0.0;   // time of the largest absolute error
  bool finite = true;      // false when the co-simulation produced NaN or Inf
};

SignalError compare_signal(std::span<const double> t, std::span<const double> cosim, std::span<const double> reference);

}  // namespace mechsim::launch
