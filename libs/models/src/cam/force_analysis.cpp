#include "mechsim/models/cam/force_analysis.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "mechsim/models/constants.h"
#include "numerics.h"

namespace mechsim::models::cam {

namespace {

// A stretch of the cycle where the law is one piece and the functional load is constant:
// every integrand below is smooth on it.
struct Span {
  double begin, end;
  std::size_t piece;
  double load_n;
};

std::vector<Span> smooth_spans(const MotionLaw& law, const std::vector<follower::FunctionalLoad>& loads) {
  std::vector<double> cuts{0.0, two_pi};
  for (const auto& p : law.pieces()) cuts.push_back(p.segment.start_rad);
  for (const auto& l : loads) {
    cuts.push_back(l.start_rad);
    cuts.push_back(l.end_rad);
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<Span> spans;
  const auto& pieces = law.pieces();
  for (std::size_t i = 1; i < cuts.size(); ++i) {
    const double a = cuts[i - 1], b = std::min(cuts[i], two_pi);
    if (b - a < 1e-9) continue;  // the same cut, written twice up to rounding
    const double mid = 0.5 * (a + b);
    std::size_t piece = 0;
    while (piece + 1 < pieces.size() && pieces[piece + 1].segment.start_rad <= mid) ++piece;
    spans.push_back({a, b, piece, follower::functional_load(loads, mid)});
  }
  return spans;
}

// Coarse sampling before refinement, and Gauss–Legendre sub-intervals: 0.05° and 0.5°.
int samples_for(const Span& s) { return std::max(4, static_cast<int>(std::ceil((s.end - s.begin) / (0.05 * degree)))); }
int quadrature_parts(double width) { return std::max(1, static_cast<int>(std::ceil(width / (0.5 * degree)))); }

using numerics::wrap;

// N cos α on a span (no ω̇: constant speed).
double normal_component(const follower::FollowerParams& f, const Span& s, const LawPoint& p, double w) {
  return s.load_n + f.spring.preload_n + f.spring.stiffness_n_per_m * p.s + f.mass * p.s_d2 * w * w;
}

void check_speed(double w) {
  if (!std::isfinite(w)) throw std::invalid_argument("cam force analysis: speed must be finite");
}

}  // namespace

ContactForceExtremes contact_force_extremes(const MotionLaw& law, const CamGeometry& g,
                                            const follower::FollowerParams& f, double w) {
  check_speed(w);
  ContactForceExtremes out{{0, 0, inf}, {0, 0, -inf}, true};
  for (const Span& s : smooth_spans(law, f.loads)) {
    auto n = [&](double t) {
      const LawPoint p = law.evaluate_piece(s.piece, t);
      return normal_component(f, s, p, w) / std::cos(pressure_angle(p.s, p.s_d1, g.pitch_radius_m, g.eccentricity_m));
    };
    const auto lo = numerics::minimise(n, s.begin, s.end, samples_for(s));
    const auto hi = numerics::maximise(n, s.begin, s.end, samples_for(s));
    if (lo.value < out.min.contact_force_n)
      out.min = {wrap(lo.x), law.evaluate_piece(s.piece, lo.x).s, lo.value};
    if (hi.value > out.max.contact_force_n)
      out.max = {wrap(hi.x), law.evaluate_piece(s.piece, hi.x).s, hi.value};
  }
  out.contact_everywhere = out.min.contact_force_n >= 0.0;
  return out;
}

SpringSizing minimum_spring_stiffness(const MotionLaw& law, const follower::FollowerParams& f,
                                      double preload_n, double w) {
  check_speed(w);
  // Below this lift S counts as zero (rounding of a law that returns to its base).
  const double zero_lift = 1e-12 * std::max(law.max_lift(), 1e-3);
  SpringSizing out{-inf, 0.0, 0.0, true};
  for (const Span& s : smooth_spans(law, f.loads)) {
    auto ratio = [&](double t) {
      const LawPoint p = law.evaluate_piece(s.piece, t);
      const double demand = -s.load_n - preload_n - f.mass * p.s_d2 * w * w;
      if (p.s > zero_lift) return demand / p.s;
      return demand > 0.0 ? inf : -inf;  // at S = 0 only the preload can help
    };
    const auto hi = numerics::maximise(ratio, s.begin, s.end, samples_for(s));
    if (hi.value > out.min_stiffness_n_per_m)
      out = {hi.value, wrap(hi.x), law.evaluate_piece(s.piece, hi.x).s, true};
  }
  out.feasible = out.min_stiffness_n_per_m != inf;
  out.min_stiffness_n_per_m = std::max(out.min_stiffness_n_per_m, 0.0);
  return out;
}

LiftOffSpeed kinetostatic_lift_off_speed(const MotionLaw& law, const follower::FollowerParams& f) {
  const auto spans = smooth_spans(law, f.loads);
  // Static part F_func + F0 + k S: negative somewhere means the contact is open at rest.
  for (const Span& s : spans) {
    auto stat = [&](double t) { return normal_component(f, s, law.evaluate_piece(s.piece, t), 0.0); };
    const auto lo = numerics::minimise(stat, s.begin, s.end, samples_for(s));
    if (lo.value < 0.0) return {0.0, wrap(lo.x), law.evaluate_piece(s.piece, lo.x).s};
  }
  LiftOffSpeed out{inf, 0.0, 0.0};
  double best = 0.0;  // max of (−m S'')/(F_func + F0 + k S); ≤ 0 means never
  for (const Span& s : spans) {
    auto ratio = [&](double t) {
      const LawPoint p = law.evaluate_piece(s.piece, t);
      const double stat = normal_component(f, s, p, 0.0);
      const double pull = -f.mass * p.s_d2;
      if (stat > 0.0) return pull / stat;
      return pull > 0.0 ? inf : -inf;
    };
    const auto hi = numerics::maximise(ratio, s.begin, s.end, samples_for(s));
    if (hi.value > best) {
      best = hi.value;
      out = {1.0 / std::sqrt(hi.value), wrap(hi.x), law.evaluate_piece(s.piece, hi.x).s};
    }
  }
  return out;
}

TorqueAnalysis drive_torque_analysis(const MotionLaw& law, const follower::FollowerParams& f, double w) {
  check_speed(w);
  const auto spans = smooth_spans(law, f.loads);
  auto torque_on = [&](const Span& s) {
    return [&, s](double t) {
      const LawPoint p = law.evaluate_piece(s.piece, t);
      return normal_component(f, s, p, w) * p.s_d1;
    };
  };
  TorqueAnalysis out{};
  out.max_torque_nm = -inf;
  out.min_torque_nm = inf;
  double total = 0.0;
  for (const Span& s : spans) {
    const auto m = torque_on(s);
    total += numerics::integrate(m, s.begin, s.end, quadrature_parts(s.end - s.begin));
    const auto hi = numerics::maximise(m, s.begin, s.end, samples_for(s));
    const auto lo = numerics::minimise(m, s.begin, s.end, samples_for(s));
    if (hi.value > out.max_torque_nm) out.max_torque_nm = hi.value, out.angle_max_torque_rad = wrap(hi.x);
    if (lo.value < out.min_torque_nm) out.min_torque_nm = lo.value, out.angle_min_torque_rad = wrap(lo.x);
  }
  out.mean_torque_nm = total / two_pi;
  out.mean_power_w = out.mean_torque_nm * w;
  out.max_power_w = std::max(out.max_torque_nm * w, out.min_torque_nm * w);

  // A(θ): candidates for its extremes are the span ends (M may jump there) and the
  // zeros of M − M_mean inside the spans.
  out.a_min_j = 0.0, out.theta_a_min_rad = 0.0;
  out.a_max_value_j = 0.0, out.theta_a_max_rad = 0.0;
  auto consider = [&](double theta, double a) {
    if (a < out.a_min_j) out.a_min_j = a, out.theta_a_min_rad = wrap(theta);
    if (a > out.a_max_value_j) out.a_max_value_j = a, out.theta_a_max_rad = wrap(theta);
  };
  double a_start = 0.0;
  for (const Span& s : spans) {
    const auto m = torque_on(s);
    auto excess = [&](double t) { return m(t) - out.mean_torque_nm; };
    auto a_at = [&](double t) {
      return a_start + numerics::integrate(excess, s.begin, t, quadrature_parts(t - s.begin));
    };
    const int n = samples_for(s);
    double prev_t = s.begin, prev = excess(prev_t);
    for (int i = 1; i <= n; ++i) {
      const double t = i == n ? s.end : s.begin + (s.end - s.begin) * i / n;
      const double v = excess(t);
      if ((prev < 0.0) != (v < 0.0)) {
        const double root = numerics::bisect(excess, prev_t, t);
        consider(root, a_at(root));
      }
      prev_t = t, prev = v;
    }
    a_start = a_at(s.end);
    consider(s.end, a_start);
  }
  out.a_max_j = out.a_max_value_j - out.a_min_j;
  return out;
}

FlywheelDesign flywheel_design(const TorqueAnalysis& torque, double k, double w, double density,
                               double thickness) {
  if (!(k > 0.0) || !(w > 0.0) || !(density > 0.0) || !(thickness > 0.0))
    throw std::invalid_argument("flywheel design: K, speed, density and thickness must be > 0");
  FlywheelDesign out{};
  out.inertia_kgm2 = torque.a_max_j / (k * w * w);
  out.disc_radius_m = std::pow(2.0 * out.inertia_kgm2 / (std::numbers::pi * thickness * density), 0.25);
  out.speed_max_rad_s = w * (1.0 + k / 2.0);
  out.theta_speed_max_rad = torque.theta_a_min_rad;
  out.speed_min_rad_s = w * (1.0 - k / 2.0);
  out.theta_speed_min_rad = torque.theta_a_max_rad;
  return out;
}

std::vector<CycleSample> sample_cycle(const MotionLaw& law, const CamGeometry& g,
                                      const follower::FollowerParams& f, double w, int count) {
  check_speed(w);
  if (count < 2) throw std::invalid_argument("sample_cycle: need at least 2 samples");
  const auto spans = smooth_spans(law, f.loads);
  const double mean = drive_torque_analysis(law, f, w).mean_torque_nm;
  std::vector<CycleSample> out;
  out.reserve(count);
  std::size_t k = 0;
  double a_span_start = 0.0;
  for (int i = 0; i < count; ++i) {
    const double th = two_pi * i / count;
    auto excess_on = [&](const Span& s) {
      return [&, s](double t) {
        const LawPoint p = law.evaluate_piece(s.piece, t);
        return normal_component(f, s, p, w) * p.s_d1 - mean;
      };
    };
    while (k + 1 < spans.size() && spans[k].end <= th) {
      a_span_start += numerics::integrate(excess_on(spans[k]), spans[k].begin, spans[k].end,
                                          quadrature_parts(spans[k].end - spans[k].begin));
      ++k;
    }
    const Span& s = spans[k];
    const LawPoint p = law.evaluate_piece(s.piece, th);
    const double alpha = pressure_angle(p.s, p.s_d1, g.pitch_radius_m, g.eccentricity_m);
    const auto forces = follower::kinetostatic_forces(f, th, p.s, p.s_d1, p.s_d2, alpha, w);
    const double spring = f.spring.preload_n + f.spring.stiffness_n_per_m * p.s;
    CycleSample c{};
    c.theta_rad = th;
    c.lift_m = p.s, c.lift_d1 = p.s_d1, c.lift_d2 = p.s_d2;
    c.pressure_angle_rad = alpha;
    c.functional_load_n = forces.functional_load_n;
    c.spring_force_n = forces.spring_force_n;
    c.inertia_force_n = forces.inertia_force_n;
    c.contact_force_n = forces.contact_force_n;
    c.contact_force_without_spring_n = (forces.normal_component_n - spring) / std::cos(alpha);
    c.drive_torque_nm = forces.drive_torque_nm;
    c.a_j = a_span_start + numerics::integrate(excess_on(s), s.begin, th, quadrature_parts(th - s.begin));
    out.push_back(c);
  }
  return out;
}

}  // namespace mechsim::models::cam
