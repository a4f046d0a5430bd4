#include "mechsim/models/cam/flat_face.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "mechsim/models/constants.h"
#include "numerics.h"

namespace mechsim::models::cam {

FlatFaceParams flat_face_example(double lift_m, double speed_rad_s) {
  return {0.040, lift_m, std::numbers::pi, speed_rad_s, 0.1, 5000.0, 20.0};
}

MotionLaw flat_face_law(const FlatFaceParams& p) {
  if (!(p.span_rad > 0.0 && 2.0 * p.span_rad <= two_pi + 1e-12))
    throw std::invalid_argument("flat-faced follower: need 0 < beta <= 180 deg (rise and return in one turn)");
  if (!(p.lift_m > 0.0)) throw std::invalid_argument("flat-faced follower: lift must be > 0");
  if (!(p.base_radius_m > 0.0)) throw std::invalid_argument("flat-faced follower: base radius must be > 0");
  return MotionLaw({{SegmentType::full_cycloid, 0.0, p.span_rad, p.lift_m},
                    {SegmentType::full_cycloid, p.span_rad, p.span_rad, -p.lift_m}});
}

namespace {
FlatFacePoint point_on(const FlatFaceParams& p, const LawPoint& s, double theta) {
  FlatFacePoint f{};
  const double w = p.speed_rad_s;
  const double x0 = p.spring_preload_n / p.spring_stiffness_n_per_m;
  f.theta_rad = theta;
  f.lift_m = s.s;
  f.offset_m = s.s_d1;
  f.acceleration = s.s_d2 * w * w;
  const double r = p.base_radius_m + s.s;
  f.contour_radius_m = std::hypot(r, s.s_d1);
  f.contour_angle_rad = theta + std::atan(s.s_d1 / r);
  f.contour = {f.contour_radius_m * std::sin(f.contour_angle_rad), f.contour_radius_m * std::cos(f.contour_angle_rad)};
  f.curvature_radius_m = r + s.s_d2;
  f.contact_force_n = p.spring_stiffness_n_per_m * (s.s + x0) + p.mass_kg * f.acceleration;
  f.torque_nm = f.contact_force_n * s.s_d1;
  f.power_w = f.torque_nm * w;
  return f;
}
}  // namespace

FlatFacePoint flat_face_point(const FlatFaceParams& p, double theta_rad) {
  if (!(p.spring_stiffness_n_per_m > 0.0)) throw std::invalid_argument("flat-faced follower: k must be > 0");
  const MotionLaw law = flat_face_law(p);
  return point_on(p, law.evaluate(theta_rad), theta_rad);
}

FlatFaceAnalysis analyse_flat_face(const FlatFaceParams& p) {
  if (!(p.spring_stiffness_n_per_m > 0.0)) throw std::invalid_argument("flat-faced follower: k must be > 0");
  const MotionLaw law = flat_face_law(p);
  const auto& pieces = law.pieces();
  FlatFaceAnalysis out{};
  out.min_contact_force_n = std::numeric_limits<double>::infinity();
  out.min_curvature_radius_m = std::numeric_limits<double>::infinity();
  out.peak_power_w = -std::numeric_limits<double>::infinity();
  auto on_piece = [&](std::size_t i, double t) { return point_on(p, law.evaluate_piece(i, t), t); };
  auto parts = [](double width) { return std::max(1, static_cast<int>(std::ceil(width / (0.5 * degree)))); };
  auto samples = [](double width) { return std::max(4, static_cast<int>(std::ceil(width / (0.05 * degree)))); };

  double total = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double a = pieces[i].segment.start_rad, b = a + pieces[i].segment.span_rad;
    total += numerics::integrate([&](double t) { return on_piece(i, t).torque_nm; }, a, b, parts(b - a));
    const auto pw = numerics::maximise([&](double t) { return on_piece(i, t).power_w; }, a, b, samples(b - a));
    if (pw.value > out.peak_power_w) out.peak_power_w = pw.value, out.angle_peak_power_rad = pw.x;
    const auto fc = numerics::minimise([&](double t) { return on_piece(i, t).contact_force_n; }, a, b, samples(b - a));
    if (fc.value < out.min_contact_force_n) out.min_contact_force_n = fc.value, out.angle_min_contact_force_rad = fc.x;
    const auto rc = numerics::minimise([&](double t) { return on_piece(i, t).curvature_radius_m; }, a, b, samples(b - a));
    out.min_curvature_radius_m = std::min(out.min_curvature_radius_m, rc.value);
    const auto q = numerics::maximise([&](double t) { return std::abs(on_piece(i, t).offset_m); }, a, b, samples(b - a));
    out.max_offset_m = std::max(out.max_offset_m, q.value);
  }
  out.mean_torque_nm = total / two_pi;
  out.contact_everywhere = out.min_contact_force_n > 0.0;

  // Positive area of M − M_mean and the swing of its integral: split each piece at the
  // zeros of M − M_mean (found on a 0.05° grid and bisected) and integrate lobe by lobe.
  double a_now = 0.0, a_min = 0.0, a_max = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double a = pieces[i].segment.start_rad, b = a + pieces[i].segment.span_rad;
    auto excess = [&](double t) { return on_piece(i, t).torque_nm - out.mean_torque_nm; };
    const int n = samples(b - a);
    double lobe_start = a, prev_t = a, prev = excess(a);
    auto close_lobe = [&](double end) {
      const double area = numerics::integrate(excess, lobe_start, end, parts(end - lobe_start));
      if (area > 0.0) out.delta_e_j += area;
      a_now += area;
      a_min = std::min(a_min, a_now), a_max = std::max(a_max, a_now);
      lobe_start = end;
    };
    for (int k = 1; k <= n; ++k) {
      const double t = k == n ? b : a + (b - a) * k / n;
      const double v = excess(t);
      if ((prev < 0.0) != (v < 0.0)) close_lobe(numerics::bisect(excess, prev_t, t));
      prev_t = t, prev = v;
    }
    close_lobe(b);
  }
  out.energy_swing_j = a_max - a_min;
  const double x0 = p.spring_preload_n / p.spring_stiffness_n_per_m;
  out.delta_e_closed_form_j = p.spring_stiffness_n_per_m * (p.lift_m * p.lift_m / 2.0 + x0 * p.lift_m);
  return out;
}

double flat_face_flywheel_inertia(const FlatFaceAnalysis& a, double w, double cs) {
  if (!(w > 0.0) || !(cs > 0.0)) throw std::invalid_argument("flywheel: speed and fluctuation must be > 0");
  return a.delta_e_j / (w * w * cs);
}

}  // namespace mechsim::models::cam
