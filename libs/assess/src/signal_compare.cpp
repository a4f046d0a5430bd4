#include "mechsim/assess/signal_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace mechsim::assess {

double relative_scale(std::span<const double> reference) {
  if (reference.empty()) return 1.0;
  const auto [lo, hi] = std::minmax_element(reference.begin(), reference.end());
  return *hi > *lo ? *hi - *lo : std::max(std::abs(*hi), 1.0);
}

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
  const double scale = relative_scale(reference);
  e.max_rel = e.max_abs / scale;
  e.rms_rel = e.rms_abs / scale;
  return e;
}

ErrorCause classify_error(std::span<const double> t, std::span<const double> cosim, std::span<const double> reference) {
  ErrorCause c;
  const std::size_t n = reference.size();
  if (n < 4 || cosim.size() != n || t.size() != n) return c;
  std::size_t worst = 0;
  double max_abs = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = std::abs(cosim[k] - reference[k]);
    if (!std::isfinite(d)) return c;  // a diverged run: no artefact to name
    if (d > max_abs) max_abs = d, worst = k;
  }
  if (max_abs == 0.0) return c;
  // One step late: compare with the reference shifted by one sample (the macro-step grid).
  for (std::size_t k = 1; k < n; ++k) c.max_abs_shifted = std::max(c.max_abs_shifted, std::abs(cosim[k] - reference[k - 1]));
  c.one_step_late = c.max_abs_shifted < 0.2 * max_abs;
  // Jumps: step-to-step changes far above the typical one.
  std::vector<double> change(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) change[k] = std::abs(reference[k + 1] - reference[k]);
  // The typical change is the median of the nonzero ones (a signal that rests for half the
  // run would otherwise make every movement a jump); a jump is also at least 2 % of the
  // reference's range.
  std::vector<double> moving;
  for (double d : change)
    if (d > 0) moving.push_back(d);
  if (moving.empty()) return c;
  std::nth_element(moving.begin(), moving.begin() + moving.size() / 2, moving.end());
  const double typical = moving[moving.size() / 2];
  const auto [lo, hi] = std::minmax_element(reference.begin(), reference.end());
  const double threshold = std::max(10 * typical, 0.02 * (*hi - *lo));
  auto is_jump = [&](std::size_t k) { return change[k] > threshold; };
  std::vector<bool> near_jump(n, false);
  for (std::size_t k = 0; k + 1 < n; ++k)
    if (is_jump(k)) {
      ++c.jumps;
      for (std::size_t j = k >= 2 ? k - 2 : 0; j <= std::min(n - 1, k + 3); ++j) near_jump[j] = true;
    }
  // The jump at the worst error: the change into or out of that sample.
  for (std::size_t k : {worst > 0 ? worst - 1 : worst, worst})
    if (k + 1 < n && is_jump(k) && change[k] >= 0.5 * max_abs) {
      c.jump = true;
      c.t_jump = t[k + 1];
      break;
    }
  for (std::size_t k = 0; k < n; ++k)
    if (!near_jump[k]) c.max_abs_away_from_jumps = std::max(c.max_abs_away_from_jumps, std::abs(cosim[k] - reference[k]));
  return c;
}

}  // namespace mechsim::assess
