// Cam motion law S(θ): a list of lift segments over one revolution (spec cam.md §1).
//
// Each segment covers [start, start + span) of the cam angle θ with a relative lift L
// (negative = fall) shaped by a normalised profile f(x), x = (θ − start)/span in [0, 1],
// f(0) = 0, f(1) = 1. Intervals no segment covers are dwells at the lift reached so far.
// S is in m, S' = dS/dθ in m/rad, S'' in m/rad², S''' in m/rad³. The law is periodic:
// it refuses to be built unless the net lift over 360° is zero.
#pragma once

#include <string>
#include <vector>

namespace mechsim::models::cam {

enum class SegmentType {
  full_cycloid,        // x − sin(2πx)/(2π): rest to rest
  half_cycloid_c1,     // x − sin(πx)/π: starts at rest, ends at speed 2L/β
  half_cycloid_c2,     // x + sin(πx)/π: starts at speed 2L/β, ends at rest
  dwell,               // constant (lift must be 0)
  harmonic,            // (1 − cos πx)/2: rest to rest, S'' jumps at both ends
  polynomial_345,      // 10x³ − 15x⁴ + 6x⁵: rest to rest, S'' continuous
  modified_sine,       // cycloid ends (1/8) joined by a slower sine flank: C_a = 5.53
  modified_trapezoid,  // sine ramps (1/8) and constant acceleration (1/4): C_a = 4.89
  constant_velocity,   // x: a ramp, S' jumps at both ends (infinite acceleration)
};

// Lower-case name as written in scenes and reports ("full_cycloid", "harmonic", ...).
const char* segment_type_name(SegmentType type);
// Inverse of segment_type_name; throws std::invalid_argument for an unknown name.
SegmentType segment_type_from_name(const std::string& name);

struct Segment {
  SegmentType type;
  double start_rad;  // in [0, 2π)
  double span_rad;   // > 0, start + span ≤ 2π
  double lift_m;     // relative lift over the segment, negative for a fall
};

// The normalised profile f(x) and its derivatives with respect to x.
struct NormalisedProfile {
  double f, f1, f2, f3;
};
// x is clamped to [0, 1]. At an internal kink of the jerk (modified sine/trapezoid) the
// value of the right-hand piece is returned.
NormalisedProfile normalised_profile(SegmentType type, double x);

// S and its θ-derivatives at one angle.
struct LawPoint {
  double s;     // m
  double s_d1;  // m/rad
  double s_d2;  // m/rad²
  double s_d3;  // m/rad³; at a joint the right-hand value (the jerk may jump there)
};

// One joint between consecutive pieces (segments or the dwells filling gaps), including
// the wrap joint at 0° = 360°. A jump is value_after − value_before.
struct Joint {
  double angle_rad;
  double jump_s, jump_s_d1, jump_s_d2, jump_s_d3;
};

struct Continuity {
  std::vector<Joint> joints;
  // Highest n such that S, S', ..., S^(n) are continuous over the whole cycle (checked up
  // to 3): 0 = S' jumps (infinite acceleration), 1 = S'' jumps (infinite jerk),
  // 2 = S'' continuous and the jerk jumps, 3 = the jerk is continuous too.
  int lowest_continuous_derivative = 3;
  bool velocity_jumps() const { return lowest_continuous_derivative < 1; }
  // A sentence such as "S'' continuous, jerk jumps".
  std::string summary() const;
};

class MotionLaw {
 public:
  // Throws std::invalid_argument (with a message that says what is wrong) for a
  // non-positive span, a segment outside [0°, 360°], overlapping segments, a dwell with a
  // lift, or a net lift over 360° that is not zero.
  explicit MotionLaw(std::vector<Segment> segments);

  // S, S', S'', S''' at any θ (wrapped periodically into [0, 2π)).
  LawPoint evaluate(double theta_rad) const;

  // The segments as given, sorted by start angle.
  const std::vector<Segment>& segments() const { return segments_; }
  // Continuity at every joint, with the default relative tolerance (see analyse_continuity).
  const Continuity& continuity() const { return continuity_; }
  // Largest |S| over the cycle (the stroke when the law starts at its lowest point).
  double max_lift() const;

  // One piece of the cycle: a segment, or a dwell filling a gap, with the lift at its start.
  struct Piece {
    Segment segment;
    double start_lift_m;
    bool filler;  // a dwell that fills a gap between given segments
  };
  const std::vector<Piece>& pieces() const { return pieces_; }
  // S and its derivatives from piece i's own formula at θ in [start, start + span] (its
  // closed interval: at the end this is the left-hand limit, which evaluate() does not give).
  LawPoint evaluate_piece(std::size_t piece_index, double theta_rad) const;

 private:
  std::vector<Segment> segments_;
  std::vector<Piece> pieces_;  // cover [0, 2π) without gaps, sorted
  Continuity continuity_;
};

// Continuity check. A jump of the n-th derivative counts when it exceeds
// relative_tolerance × the natural scale max|L|/β^n of the law's segments.
Continuity analyse_continuity(const MotionLaw& law, double relative_tolerance = 1e-9);

// Span of a C1 half cycloid whose end slope 2 L1/β1 matches the start slope 2 L2/β2 of the
// following C2: β1 = β2 L1/L2 (spec §1: 18.75° for the press cam).
double matched_c1_span(double c1_lift_m, double c2_span_rad, double c2_lift_m);

double deg_to_rad(double deg);
double rad_to_deg(double rad);

}  // namespace mechsim::models::cam
