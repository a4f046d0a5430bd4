#include "mechsim/models/cam/motion_law.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {
namespace {

constexpr double pi = std::numbers::pi;
// Closed forms evaluated with a handful of double operations on O(10) numbers: rounding
// stays below 1e-14, so 1e-12 can only fail on a wrong formula.
constexpr double closed_form_tol = 1e-12;

struct Expected {
  double x, f, f1, f2;
};

void expect_profile(SegmentType type, std::initializer_list<Expected> values) {
  for (const Expected& e : values) {
    const NormalisedProfile p = normalised_profile(type, e.x);
    SCOPED_TRACE(std::string(segment_type_name(type)) + " at x = " + std::to_string(e.x));
    EXPECT_NEAR(p.f, e.f, closed_form_tol);
    EXPECT_NEAR(p.f1, e.f1, closed_form_tol);
    EXPECT_NEAR(p.f2, e.f2, closed_form_tol);
  }
}

TEST(NormalisedProfile, ClosedFormsAtStartMiddleEnd) {
  expect_profile(SegmentType::full_cycloid, {{0, 0, 0, 0}, {0.5, 0.5, 2, 0}, {1, 1, 0, 0}});
  expect_profile(SegmentType::half_cycloid_c1,
                 {{0, 0, 0, 0}, {0.5, 0.5 - 1 / pi, 1, pi}, {1, 1, 2, 0}});
  expect_profile(SegmentType::half_cycloid_c2,
                 {{0, 0, 2, 0}, {0.5, 0.5 + 1 / pi, 1, -pi}, {1, 1, 0, 0}});
  expect_profile(SegmentType::dwell, {{0, 0, 0, 0}, {0.5, 0, 0, 0}, {1, 0, 0, 0}});
  expect_profile(SegmentType::harmonic,
                 {{0, 0, 0, pi * pi / 2}, {0.5, 0.5, pi / 2, 0}, {1, 1, 0, -pi * pi / 2}});
  expect_profile(SegmentType::polynomial_345, {{0, 0, 0, 0}, {0.5, 0.5, 1.875, 0}, {1, 1, 0, 0}});
  // Modified sine: peak velocity 4π/(4+π) = 1.76 at the middle, peak acceleration
  // 4π²/(4+π) = 5.53 at x = 1/8 (Norton's C_v and C_a).
  expect_profile(SegmentType::modified_sine,
                 {{0, 0, 0, 0},
                  {0.125, (pi / 8 - 0.25) / (4 + pi), pi / (4 + pi), 4 * pi * pi / (4 + pi)},
                  {0.5, 0.5, 4 * pi / (4 + pi), 0},
                  {1, 1, 0, 0}});
  // Modified trapezoid: peak velocity 2 at the middle, constant acceleration 8π/(2+π) = 4.89
  // on [1/8, 3/8].
  expect_profile(SegmentType::modified_trapezoid, {{0, 0, 0, 0}, {0.5, 0.5, 2, 0}, {1, 1, 0, 0}});
  EXPECT_NEAR(normalised_profile(SegmentType::modified_trapezoid, 0.25).f2, 8 * pi / (2 + pi),
              closed_form_tol);
  expect_profile(SegmentType::constant_velocity, {{0, 0, 1, 0}, {0.5, 0.5, 1, 0}, {1, 1, 1, 0}});
}

// Each derivative must be the derivative of the one before: central differences with
// h = 1e-5 have a truncation error ≈ h² |f'''|/6 < 1e-8 (|f'''| < 2000 for every profile)
// and a rounding error ≈ 1e-16 · max|f|/h < 1e-9 (max|f''| < 40): 1e-6 is a safe bound.
TEST(NormalisedProfile, DerivativesAreConsistent) {
  const double h = 1e-5;
  for (SegmentType type :
       {SegmentType::full_cycloid, SegmentType::half_cycloid_c1, SegmentType::half_cycloid_c2,
        SegmentType::harmonic, SegmentType::polynomial_345, SegmentType::modified_sine,
        SegmentType::modified_trapezoid, SegmentType::constant_velocity}) {
    // Points away from the internal joints at multiples of 1/8 (where f''' may jump).
    for (double x = 0.01; x < 1.0; x += 0.0371) {
      SCOPED_TRACE(std::string(segment_type_name(type)) + " at x = " + std::to_string(x));
      const NormalisedProfile m = normalised_profile(type, x - h);
      const NormalisedProfile p = normalised_profile(type, x + h);
      const NormalisedProfile c = normalised_profile(type, x);
      EXPECT_NEAR((p.f - m.f) / (2 * h), c.f1, 1e-6);
      EXPECT_NEAR((p.f1 - m.f1) / (2 * h), c.f2, 1e-6 * 40);
      EXPECT_NEAR((p.f2 - m.f2) / (2 * h), c.f3, 1e-6 * 2000);
    }
  }
}

// The piecewise laws join their pieces with continuous f, f', f'' (that is their point).
TEST(NormalisedProfile, PiecewiseLawsAreSmoothInside) {
  for (SegmentType type : {SegmentType::modified_sine, SegmentType::modified_trapezoid}) {
    for (double joint : {0.125, 0.375, 0.5, 0.625, 0.875}) {
      SCOPED_TRACE(std::string(segment_type_name(type)) + " at x = " + std::to_string(joint));
      const NormalisedProfile l = normalised_profile(type, joint - 1e-12);
      const NormalisedProfile r = normalised_profile(type, joint + 1e-12);
      // A step of 2e-12 in x changes a C² function by at most 2e-12 · max|f'''| ≈ 1e-9.
      EXPECT_NEAR(l.f, r.f, 1e-9);
      EXPECT_NEAR(l.f1, r.f1, 1e-9);
      EXPECT_NEAR(l.f2, r.f2, 1e-9);
    }
  }
}

TEST(MotionLaw, MatchedC1SpanIsTheReportValue) {
  // β1 = β2 L1/L2 = 75° · 5/20 = 18.75° exactly; only deg/rad rounding remains.
  EXPECT_NEAR(rad_to_deg(matched_c1_span(0.005, deg_to_rad(75.0), 0.020)), 18.75, 1e-12);
}

TEST(MotionLaw, PressCamValuesAtTheJoints) {
  const MotionLaw law = PressCam{}.law();
  // Lifts at the joints follow from the segment lifts (exact up to rounding).
  EXPECT_NEAR(law.evaluate(deg_to_rad(10.0)).s, 0.0, 1e-15);
  EXPECT_NEAR(law.evaluate(deg_to_rad(45.0)).s, 0.005, 1e-15);
  EXPECT_NEAR(law.evaluate(deg_to_rad(130.0)).s, 0.025, 1e-15);
  EXPECT_NEAR(law.evaluate(deg_to_rad(300.0)).s, 0.0, 1e-15);
  // The C1/C2 joint speed: 2 L2/β2 = 0.04/(75° in rad) m/rad.
  EXPECT_NEAR(law.evaluate(deg_to_rad(45.0)).s_d1, 0.04 / deg_to_rad(75.0), 1e-14);
  // Periodic wrap: θ and θ ± 2π give the same point.
  const LawPoint a = law.evaluate(deg_to_rad(170.0));
  const LawPoint b = law.evaluate(deg_to_rad(170.0) + 4 * pi);
  const LawPoint c = law.evaluate(deg_to_rad(170.0) - 2 * pi);
  EXPECT_NEAR(a.s, b.s, 1e-15);
  EXPECT_NEAR(a.s_d2, c.s_d2, 1e-12);
  EXPECT_NEAR(law.max_lift(), 0.025, 1e-15);
}

TEST(MotionLaw, PressCamIsContinuousUpToSecondDerivative) {
  const MotionLaw law = PressCam{}.law();
  const Continuity& c = law.continuity();
  EXPECT_EQ(c.lowest_continuous_derivative, 2) << c.summary();
  EXPECT_FALSE(c.velocity_jumps());
  EXPECT_EQ(c.summary(), "S'' continuous, jerk jumps");
  // Joints: 26.25 (dwell/C1), 45 (C1/C2), 120, 140, 210, 360 = 0 (wrap).
  ASSERT_EQ(c.joints.size(), 6u);
  for (const Joint& j : c.joints) {
    SCOPED_TRACE("joint at " + std::to_string(rad_to_deg(j.angle_rad)) + " deg");
    EXPECT_LT(std::abs(j.jump_s), 1e-15);
    EXPECT_LT(std::abs(j.jump_s_d1), 1e-14);
    EXPECT_LT(std::abs(j.jump_s_d2), 1e-12);
    // The wrap joint joins the closing dwell to the opening dwell: nothing jumps there.
    if (j.angle_rad == 0.0) {
      EXPECT_EQ(j.jump_s_d3, 0.0);
      continue;
    }
    // The report: the jerk jumps at every other joint. The smallest jump is at the C1/C2 joint:
    // π²(L1/β1³ − L2/β2³) = 1.2 m/rad³; the others are π² L/β³ or 4π² L/β³ of a segment
    // end, all above 1 m/rad³. 1e-3 separates a jump from rounding (< 1e-10).
    EXPECT_GT(std::abs(j.jump_s_d3), 1e-3);
  }
}

TEST(MotionLaw, RefusesANonClosingLaw) {
  std::vector<Segment> segments = press_cam_segments();
  segments.back().lift_m = -0.020;  // falls 20 mm after rising 25 mm
  try {
    MotionLaw law(segments);
    FAIL() << "a law that does not close was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "net lift over 360 deg is 5 mm, must be 0: the law does not close");
  }
}

TEST(MotionLaw, RefusesBadSegments) {
  const double d = deg_to_rad(1.0);
  // Overlap.
  EXPECT_THROW(MotionLaw({{SegmentType::full_cycloid, 10 * d, 50 * d, 0.01},
                          {SegmentType::full_cycloid, 50 * d, 50 * d, -0.01}}),
               std::invalid_argument);
  // Non-positive span.
  EXPECT_THROW(MotionLaw({{SegmentType::full_cycloid, 10 * d, 0.0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(MotionLaw({{SegmentType::full_cycloid, 10 * d, -5 * d, 0.0}}), std::invalid_argument);
  // Beyond 360°.
  EXPECT_THROW(MotionLaw({{SegmentType::full_cycloid, 300 * d, 40 * d, 0.01},
                          {SegmentType::full_cycloid, 340 * d, 30 * d, -0.01}}),
               std::invalid_argument);
  // A dwell with a lift.
  EXPECT_THROW(MotionLaw({{SegmentType::dwell, 10 * d, 40 * d, 0.01},
                          {SegmentType::full_cycloid, 60 * d, 30 * d, -0.01}}),
               std::invalid_argument);
  // Touching segments are accepted.
  EXPECT_NO_THROW(MotionLaw({{SegmentType::full_cycloid, 10 * d, 40 * d, 0.01},
                             {SegmentType::full_cycloid, 50 * d, 30 * d, -0.01}}));
}

TEST(MotionLaw, DetectsAVelocityJump) {
  const double d = deg_to_rad(1.0);
  // A constant-velocity rise and fall: S' jumps at every joint (infinite acceleration).
  const MotionLaw ramp({{SegmentType::constant_velocity, 0.0, 180 * d, 0.01},
                        {SegmentType::constant_velocity, 180 * d, 180 * d, -0.01}});
  EXPECT_EQ(ramp.continuity().lowest_continuous_derivative, 0);
  EXPECT_TRUE(ramp.continuity().velocity_jumps());
  // Two C1 segments: the first ends at speed 2L/β and the second starts at rest.
  const MotionLaw c1c1({{SegmentType::half_cycloid_c1, 0.0, 90 * d, 0.01},
                        {SegmentType::full_cycloid, 90 * d, 90 * d, -0.01}});
  EXPECT_EQ(c1c1.continuity().lowest_continuous_derivative, 0);
}

TEST(MotionLaw, DetectsAnAccelerationJump) {
  const double d = deg_to_rad(1.0);
  // Harmonic rise and fall with dwells: S'' jumps from 0 to π²L/(2β²) at each end.
  const MotionLaw law({{SegmentType::harmonic, 30 * d, 90 * d, 0.01},
                       {SegmentType::harmonic, 200 * d, 90 * d, -0.01}});
  EXPECT_EQ(law.continuity().lowest_continuous_derivative, 1);
  // 3-4-5 rise and fall: S'' continuous, the jerk jumps (60 L/β³ at the ends).
  const MotionLaw poly({{SegmentType::polynomial_345, 30 * d, 90 * d, 0.01},
                        {SegmentType::polynomial_345, 200 * d, 90 * d, -0.01}});
  EXPECT_EQ(poly.continuity().lowest_continuous_derivative, 2);
}

TEST(MotionLaw, SegmentNamesRoundTrip) {
  for (SegmentType t : {SegmentType::full_cycloid, SegmentType::half_cycloid_c1,
                        SegmentType::half_cycloid_c2, SegmentType::dwell, SegmentType::harmonic,
                        SegmentType::polynomial_345, SegmentType::modified_sine,
                        SegmentType::modified_trapezoid, SegmentType::constant_velocity})
    EXPECT_EQ(segment_type_from_name(segment_type_name(t)), t);
  EXPECT_THROW(segment_type_from_name("cycloid"), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::cam
