#include "stateless_events.h"

namespace mechsim::solve::detail {

namespace {

// +1 rising, -1 falling, 0 none, of g from a to b, as the function's direction admits.
int crossing(double a, double b, models::Crossing direction) {
  const int c = (a < 0 && b >= 0) ? 1 : (a > 0 && b <= 0) ? -1 : 0;
  if (c > 0 && direction == models::Crossing::falling) return 0;
  if (c < 0 && direction == models::Crossing::rising) return 0;
  return c;
}

bool any_crossing(std::span<const double> from, std::span<const double> to, std::span<const models::Crossing> directions) {
  for (std::size_t i = 0; i < from.size(); ++i)
    if (crossing(from[i], to[i], directions[i]) != 0) return true;
  return false;
}

}  // namespace

std::optional<double> first_stateless_crossing(const std::function<void(double, std::span<double>)>& g_at,
                                               std::span<const models::Crossing> directions, double t, double target,
                                               double resolution, std::span<int> crossed) {
  const std::size_t n = directions.size();
  std::vector<double> g0(n), g_hi(n), g_mid(n);
  g_at(t, g0);
  double hi = target;
  g_at(hi, g_hi);
  if (!any_crossing(g0, g_hi, directions)) {
    g_at(target + resolution, g_hi);
    if (!any_crossing(g0, g_hi, directions)) return std::nullopt;
    hi = target + resolution;
  }
  // Bisection keeps [lo, hi] around the first crossing: none in [t, lo], one by hi.
  double lo = t;
  while (hi - lo > resolution) {
    const double mid = lo + 0.5 * (hi - lo);
    g_at(mid, g_mid);
    if (any_crossing(g0, g_mid, directions)) {
      hi = mid;
      g_hi = g_mid;
    } else {
      lo = mid;
    }
  }
  for (std::size_t i = 0; i < n; ++i) crossed[i] = crossing(g0[i], g_hi[i], directions[i]);
  return std::min(hi, target);
}

}  // namespace mechsim::solve::detail
