// Small numerical tools shared by the cam design analyses (private to the library).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <utility>

#include "mechsim/models/constants.h"

namespace mechsim::models::cam::numerics {

// An angle in [0, 2 pi).
inline double wrap(double theta) {
  double t = std::fmod(theta, two_pi);
  return t < 0.0 ? t + two_pi : (t >= two_pi ? 0.0 : t);
}

struct Located {
  double x, value;
};

// Maximum of f on [a, b]: f is sampled on n + 1 points and the best sample is refined by
// golden-section search between its neighbours (f is smooth there; a kink only costs
// the search its speed). The result is as good as the bracket: ~1e-12 of b − a.
template <typename F>
Located maximise(F&& f, double a, double b, int n) {
  n = std::max(n, 2);
  const double h = (b - a) / n;
  int best = 0;
  double best_value = f(a);
  for (int i = 1; i <= n; ++i) {
    const double v = f(i == n ? b : a + i * h);
    if (v > best_value) best_value = v, best = i;
  }
  double lo = std::max(a, a + (best - 1) * h), hi = std::min(b, a + (best + 1) * h);
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 80 && hi - lo > 1e-13 * std::max(1.0, std::abs(hi)); ++it) {
    if (f1 < f2) {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = f(x2);
    } else {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = f(x1);
    }
  }
  Located out{best == n ? b : a + best * h, best_value};
  const double mid = 0.5 * (lo + hi), fm = f(mid);
  if (fm > out.value) out = {mid, fm};
  return out;
}

template <typename F>
Located minimise(F&& f, double a, double b, int n) {
  Located m = maximise([&](double x) { return -f(x); }, a, b, n);
  return {m.x, -m.value};
}

// Root of f on [a, b] with f(a), f(b) of opposite signs (bisection: robust, 1e-15 relative).
template <typename F>
double bisect(F&& f, double a, double b) {
  double fa = f(a);
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    const double fm = f(m);
    if ((fm < 0.0) == (fa < 0.0)) a = m, fa = fm;
    else b = m;
  }
  return 0.5 * (a + b);
}

// ∫_a^b f by 5-point Gauss–Legendre on n equal sub-intervals (exact for degree 9 per
// sub-interval: the smooth cam integrands converge far below rounding with modest n).
template <typename F>
double integrate(F&& f, double a, double b, int n) {
  static constexpr std::array<double, 5> x{0.0, -0.5384693101056831, 0.5384693101056831,
                                           -0.9061798459386640, 0.9061798459386640};
  static constexpr std::array<double, 5> w{0.5688888888888889, 0.4786286704993665,
                                           0.4786286704993665, 0.2369268850561891,
                                           0.2369268850561891};
  n = std::max(n, 1);
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double c = a + (i + 0.5) * h;
    for (int k = 0; k < 5; ++k) sum += w[k] * f(c + 0.5 * h * x[k]);
  }
  return 0.5 * h * sum;
}

}  // namespace mechsim::models::cam::numerics
