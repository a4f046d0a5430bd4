#include "signal_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mechsim::launch {

SignalError compare_signal(std::span<const double> t, std::span<const double> cosim, std::span<const double> reference) {
  if (cosim.size() != reference.size() || t.size() != reference.size())
    throw std::invalid_argument("compare_signal: series of different lengths");
  SignalError e;
  if (reference.empty()) return e;
  auto [lo, hi] = std::minmax_element(reference.begin(), reference.end());
  e.range = *hi - *lo;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (!std::isfinite(cosim[i])) e.finite = false;
    const double d = std::abs(cosim[i] - reference[i]);
    if (d > e.max_abs || !std::isfinite(d)) {
      e.max_abs = std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
      e.t_of_max = t[i];
    }
    sum_sq += d * d;
  }
  e.rms_abs = std::sqrt(sum_sq / static_cast<double>(reference.size()));
  // A constant reference has no range: fall back to its magnitude (or 1) so the relative
  // figure stays defined.
  const double scale = e.range > 0 ? e.range : std::max(std::abs(*hi), 1.0);
  e.max_rel = e.max_abs / scale;
  e.rms_rel = e.rms_abs / scale;
  return e;
}

}  // namespace mechsim::launch
