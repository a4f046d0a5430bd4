#include "mechsim/models/cam/motion_law.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "mechsim/models/constants.h"

namespace mechsim::models::cam {

namespace {

// Angles built from degrees (26.25° + 18.75° = 45°) differ by rounding only: joints closer
// than this are the same joint.
constexpr double angle_tolerance = 1e-9;

// First half (x ≤ 1/2) of the modified sine; the second half follows by symmetry.
NormalisedProfile modified_sine_first_half(double x) {
  const double c = 4.0 + pi;
  if (x <= 0.125) {
    const double a = 4.0 * pi * x;
    return {(pi * x - std::sin(a) / 4.0) / c, pi * (1.0 - std::cos(a)) / c,
            4.0 * pi * pi * std::sin(a) / c, 16.0 * pi * pi * pi * std::cos(a) / c};
  }
  const double a = pi / 3.0 + 4.0 * pi * x / 3.0;
  return {(2.0 + pi * x - 2.25 * std::sin(a)) / c, pi * (1.0 - 3.0 * std::cos(a)) / c,
          4.0 * pi * pi * std::sin(a) / c, 16.0 * pi * pi * pi / 3.0 * std::cos(a) / c};
}

// First half of the modified trapezoid: acceleration A sin(4πx) up to 1/8, A up to 3/8,
// A cos(4π(x − 3/8)) down to 0 at 1/2; A = 8π/(2 + π) makes f(1/2) = 1/2.
NormalisedProfile modified_trapezoid_first_half(double x) {
  const double A = 8.0 * pi / (2.0 + pi);
  const double w = 4.0 * pi;
  const double v1 = A / w, s1 = A / w * (0.125 - 1.0 / w);  // at x = 1/8
  const double v2 = v1 + A * 0.25, s2 = s1 + v1 * 0.25 + A * 0.25 * 0.25 / 2.0;  // at 3/8
  if (x <= 0.125)
    return {A / w * (x - std::sin(w * x) / w), A / w * (1.0 - std::cos(w * x)), A * std::sin(w * x),
            A * w * std::cos(w * x)};
  if (x <= 0.375) {
    const double u = x - 0.125;
    return {s1 + v1 * u + A * u * u / 2.0, v1 + A * u, A, 0.0};
  }
  const double u = x - 0.375;
  return {s2 + v2 * u + A / (w * w) * (1.0 - std::cos(w * u)), v2 + A / w * std::sin(w * u),
          A * std::cos(w * u), -A * w * std::sin(w * u)};
}

// Rest-to-rest laws with an acceleration antisymmetric about x = 1/2: f(x) = 1 − f(1 − x).
template <typename FirstHalf>
NormalisedProfile symmetric(double x, FirstHalf first_half) {
  if (x <= 0.5) return first_half(x);
  const NormalisedProfile m = first_half(1.0 - x);
  return {1.0 - m.f, m.f1, -m.f2, m.f3};
}

std::string format_mm(double metres) {
  std::ostringstream os;
  os.precision(6);
  os << metres * 1e3 << " mm";
  return os.str();
}

std::string format_deg(double rad) {
  std::ostringstream os;
  os.precision(6);
  os << rad_to_deg(rad) << " deg";
  return os.str();
}

LawPoint evaluate_piece_formula(const MotionLaw::Piece& piece, double theta) {
  const Segment& seg = piece.segment;
  const double x = (theta - seg.start_rad) / seg.span_rad;
  const NormalisedProfile p = normalised_profile(seg.type, x);
  const double b = seg.span_rad, L = seg.lift_m;
  return {piece.start_lift_m + L * p.f, L * p.f1 / b, L * p.f2 / (b * b), L * p.f3 / (b * b * b)};
}

}  // namespace

double deg_to_rad(double deg) { return deg * pi / 180.0; }
double rad_to_deg(double rad) { return rad * 180.0 / pi; }

const char* segment_type_name(SegmentType type) {
  switch (type) {
    case SegmentType::full_cycloid: return "full_cycloid";
    case SegmentType::half_cycloid_c1: return "half_cycloid_c1";
    case SegmentType::half_cycloid_c2: return "half_cycloid_c2";
    case SegmentType::dwell: return "dwell";
    case SegmentType::harmonic: return "harmonic";
    case SegmentType::polynomial_345: return "polynomial_345";
    case SegmentType::modified_sine: return "modified_sine";
    case SegmentType::modified_trapezoid: return "modified_trapezoid";
    case SegmentType::constant_velocity: return "constant_velocity";
  }
  return "unknown";
}

SegmentType segment_type_from_name(const std::string& name) {
  for (SegmentType t : {SegmentType::full_cycloid, SegmentType::half_cycloid_c1,
                        SegmentType::half_cycloid_c2, SegmentType::dwell, SegmentType::harmonic,
                        SegmentType::polynomial_345, SegmentType::modified_sine,
                        SegmentType::modified_trapezoid, SegmentType::constant_velocity})
    if (name == segment_type_name(t)) return t;
  throw std::invalid_argument(
      "unknown motion law segment type '" + name +
      "' (expected full_cycloid, half_cycloid_c1, half_cycloid_c2, dwell, harmonic, "
      "polynomial_345, modified_sine, modified_trapezoid or constant_velocity)");
}

NormalisedProfile normalised_profile(SegmentType type, double x) {
  x = std::clamp(x, 0.0, 1.0);
  switch (type) {
    case SegmentType::full_cycloid: {
      const double a = two_pi * x;
      return {x - std::sin(a) / two_pi, 1.0 - std::cos(a), two_pi * std::sin(a),
              two_pi * two_pi * std::cos(a)};
    }
    case SegmentType::half_cycloid_c1: {
      const double a = pi * x;
      return {x - std::sin(a) / pi, 1.0 - std::cos(a), pi * std::sin(a), pi * pi * std::cos(a)};
    }
    case SegmentType::half_cycloid_c2: {
      const double a = pi * x;
      return {x + std::sin(a) / pi, 1.0 + std::cos(a), -pi * std::sin(a), -pi * pi * std::cos(a)};
    }
    case SegmentType::dwell: return {0.0, 0.0, 0.0, 0.0};
    case SegmentType::harmonic: {
      const double a = pi * x;
      return {(1.0 - std::cos(a)) / 2.0, pi / 2.0 * std::sin(a), pi * pi / 2.0 * std::cos(a),
              -pi * pi * pi / 2.0 * std::sin(a)};
    }
    case SegmentType::polynomial_345: {
      const double x2 = x * x, x3 = x2 * x;
      return {10.0 * x3 - 15.0 * x3 * x + 6.0 * x3 * x2, 30.0 * x2 - 60.0 * x3 + 30.0 * x2 * x2,
              60.0 * x - 180.0 * x2 + 120.0 * x3, 60.0 - 360.0 * x + 360.0 * x2};
    }
    case SegmentType::modified_sine: return symmetric(x, modified_sine_first_half);
    case SegmentType::modified_trapezoid: return symmetric(x, modified_trapezoid_first_half);
    case SegmentType::constant_velocity: return {x, 1.0, 0.0, 0.0};
  }
  throw std::invalid_argument("normalised_profile: unknown segment type");
}

MotionLaw::MotionLaw(std::vector<Segment> segments) : segments_(std::move(segments)) {
  if (segments_.empty()) throw std::invalid_argument("motion law: no segments");
  std::sort(segments_.begin(), segments_.end(),
            [](const Segment& a, const Segment& b) { return a.start_rad < b.start_rad; });
  double net_lift = 0.0, lift_scale = 0.0;
  for (const Segment& s : segments_) {
    const std::string where = std::string(segment_type_name(s.type)) + " segment at " +
                              format_deg(s.start_rad);
    if (!std::isfinite(s.start_rad) || !std::isfinite(s.span_rad) || !std::isfinite(s.lift_m))
      throw std::invalid_argument("motion law: " + where + " has a non-finite value");
    if (!(s.span_rad > 0.0))
      throw std::invalid_argument("motion law: " + where + " has span " + format_deg(s.span_rad) +
                                  ", must be positive");
    if (s.start_rad < -angle_tolerance || s.start_rad + s.span_rad > two_pi + angle_tolerance)
      throw std::invalid_argument("motion law: " + where + " spans " + format_deg(s.start_rad) +
                                  " to " + format_deg(s.start_rad + s.span_rad) +
                                  ", beyond [0, 360] deg");
    if (s.type == SegmentType::dwell && s.lift_m != 0.0)
      throw std::invalid_argument("motion law: " + where + " is a dwell with lift " +
                                  format_mm(s.lift_m) + ", must be 0");
    net_lift += s.lift_m;
    lift_scale = std::max(lift_scale, std::abs(s.lift_m));
  }
  for (std::size_t i = 1; i < segments_.size(); ++i) {
    const Segment& a = segments_[i - 1];
    const Segment& b = segments_[i];
    if (b.start_rad < a.start_rad + a.span_rad - angle_tolerance)
      throw std::invalid_argument(
          "motion law: segments overlap: " + std::string(segment_type_name(a.type)) + " " +
          format_deg(a.start_rad) + " to " + format_deg(a.start_rad + a.span_rad) + " and " +
          segment_type_name(b.type) + " from " + format_deg(b.start_rad));
  }
  // Summing lifts rounds at the 1e-16 relative level; anything above 1e-12 is a real error.
  if (std::abs(net_lift) > 1e-12 * std::max(lift_scale, 1e-3))
    throw std::invalid_argument("net lift over 360 deg is " + format_mm(net_lift) +
                                ", must be 0: the law does not close");

  // Pieces covering [0, 2π): the segments plus dwells for the gaps.
  double angle = 0.0, lift = 0.0;
  auto add_filler = [&](double until) {
    if (until - angle > angle_tolerance)
      pieces_.push_back({{SegmentType::dwell, angle, until - angle, 0.0}, lift, true});
  };
  for (const Segment& s : segments_) {
    add_filler(s.start_rad);
    Segment snapped = s;  // a start within rounding of the previous end continues it
    if (std::abs(s.start_rad - angle) <= angle_tolerance && angle > 0.0) snapped.start_rad = angle;
    pieces_.push_back({snapped, lift, false});
    lift += s.lift_m;
    angle = snapped.start_rad + snapped.span_rad;
  }
  add_filler(two_pi);
  continuity_ = analyse_continuity(*this);
}

LawPoint MotionLaw::evaluate(double theta_rad) const {
  double theta = std::fmod(theta_rad, two_pi);
  if (theta < 0.0) theta += two_pi;
  if (theta >= two_pi) theta = 0.0;  // fmod of a value just below a multiple of 2π
  // Last piece whose start ≤ θ: pieces are half-open [start, end).
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), theta,
                             [](double t, const Piece& p) { return t < p.segment.start_rad; });
  const Piece& piece = it == pieces_.begin() ? pieces_.front() : *(it - 1);
  return evaluate_piece_formula(piece, theta);
}

LawPoint MotionLaw::evaluate_piece(std::size_t piece_index, double theta_rad) const {
  return evaluate_piece_formula(pieces_.at(piece_index), theta_rad);
}

double MotionLaw::max_lift() const {
  double m = 0.0;
  for (const Piece& p : pieces_) {
    m = std::max({m, std::abs(p.start_lift_m), std::abs(p.start_lift_m + p.segment.lift_m)});
    // Profiles that overshoot [0, 1] do not exist among the segment types, but a sampled
    // check keeps this honest should one be added.
    for (int k = 1; k < 16; ++k)
      m = std::max(m, std::abs(evaluate_piece_formula(p, p.segment.start_rad + p.segment.span_rad * k / 16.0).s));
  }
  return m;
}

Continuity analyse_continuity(const MotionLaw& law, double relative_tolerance) {
  const auto& pieces = law.pieces();
  double scale[4] = {0.0, 0.0, 0.0, 0.0};
  for (const auto& p : pieces) {
    const double L = std::abs(p.segment.lift_m), b = p.segment.span_rad;
    scale[0] = std::max(scale[0], L);
    scale[1] = std::max(scale[1], L / b);
    scale[2] = std::max(scale[2], L / (b * b));
    scale[3] = std::max(scale[3], L / (b * b * b));
  }
  Continuity c;
  int lowest = 3;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& before = pieces[i];
    const auto& after = pieces[(i + 1) % pieces.size()];
    const double end = before.segment.start_rad + before.segment.span_rad;
    const LawPoint l = evaluate_piece_formula(before, end);
    const LawPoint r = evaluate_piece_formula(after, after.segment.start_rad);
    Joint j{std::fmod(end, two_pi), r.s - l.s, r.s_d1 - l.s_d1, r.s_d2 - l.s_d2, r.s_d3 - l.s_d3};
    const double jumps[4] = {j.jump_s, j.jump_s_d1, j.jump_s_d2, j.jump_s_d3};
    for (int n = 0; n < 4; ++n)
      if (std::abs(jumps[n]) > relative_tolerance * scale[n]) {
        lowest = std::min(lowest, n - 1);
        break;
      }
    c.joints.push_back(j);
  }
  std::sort(c.joints.begin(), c.joints.end(),
            [](const Joint& a, const Joint& b) { return a.angle_rad < b.angle_rad; });
  c.lowest_continuous_derivative = lowest;
  return c;
}

std::string Continuity::summary() const {
  switch (lowest_continuous_derivative) {
    case -1: return "S jumps";
    case 0: return "S continuous, S' jumps (infinite acceleration)";
    case 1: return "S' continuous, S'' jumps (infinite jerk)";
    case 2: return "S'' continuous, jerk jumps";
    default: return "jerk continuous";
  }
}

double matched_c1_span(double c1_lift_m, double c2_span_rad, double c2_lift_m) {
  if (c2_lift_m == 0.0 || c1_lift_m / c2_lift_m <= 0.0)
    throw std::invalid_argument("matched_c1_span: C1 and C2 lifts must be non-zero and of one sign");
  return c2_span_rad * c1_lift_m / c2_lift_m;
}

}  // namespace mechsim::models::cam
