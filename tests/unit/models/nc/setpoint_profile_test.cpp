// NC interpolator profiles (spec nc_slide.md §3).
#include "mechsim/models/nc/setpoint_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mechsim::models::nc {
namespace {

// All profiles are closed-form: round-off only (1e-12 m on millimetre travels).
constexpr double tol = 1e-12;

TEST(SetpointProfileTest, StepJumpsAtStartTime) {
  SetpointProfile p{SetpointKind::step, 0.01, 1e-4};
  EXPECT_EQ(p.position(0.0099), 0.0);
  EXPECT_EQ(p.position(0.01), 1e-4);
  EXPECT_EQ(p.velocity_at(0.02), 0.0);
  EXPECT_EQ(p.move_duration(), 0.0);
}

TEST(SetpointProfileTest, RampStopsAtTheTarget) {
  SetpointProfile p{SetpointKind::ramp, 0.0, -2e-3, 0.1};
  EXPECT_NEAR(p.position(0.01), -1e-3, tol);
  EXPECT_NEAR(p.velocity_at(0.01), -0.1, tol);
  EXPECT_NEAR(p.position(0.05), -2e-3, tol);
  EXPECT_EQ(p.velocity_at(0.05), 0.0);
  EXPECT_NEAR(p.move_duration(), 0.02, tol);
}

TEST(SetpointProfileTest, TrapezoidOfTheFollowingErrorStudy) {
  // 20 mm at 100 mm/s with 1 m/s²: 0.1 s accelerating (5 mm), 0.1 s cruising, 0.1 s braking.
  SetpointProfile p{SetpointKind::trapezoid, 0.0, 0.02, 0.1, 1.0};
  EXPECT_NEAR(p.move_duration(), 0.3, tol);
  EXPECT_NEAR(p.position(0.05), 0.5 * 1.0 * 0.05 * 0.05, tol);
  EXPECT_NEAR(p.position(0.1), 5e-3, tol);
  EXPECT_NEAR(p.position(0.15), 10e-3, tol);
  EXPECT_NEAR(p.velocity_at(0.15), 0.1, tol);
  EXPECT_NEAR(p.position(0.25), 0.02 - 0.5 * 0.05 * 0.05, tol);
  EXPECT_NEAR(p.velocity_at(0.25), 0.05, tol);
  EXPECT_NEAR(p.position(1.0), 0.02, tol);
}

TEST(SetpointProfileTest, ShortTrapezoidBecomesATriangle) {
  // 1 mm cannot reach 100 mm/s at 1 m/s² (needs 10 mm): peak √(d a) = 31.6 mm/s.
  SetpointProfile p{SetpointKind::trapezoid, 0.0, -1e-3, 0.1, 1.0};
  const double t_peak = std::sqrt(1e-3 / 1.0);
  EXPECT_NEAR(p.move_duration(), 2 * t_peak, tol);
  EXPECT_NEAR(p.velocity_at(t_peak), -std::sqrt(1e-3), 1e-9);
  EXPECT_NEAR(p.position(t_peak), -0.5e-3, tol);
  EXPECT_NEAR(p.position(2 * t_peak), -1e-3, tol);
}

TEST(SetpointProfileTest, VelocityIsTheDerivativeOfPosition) {
  SetpointProfile p{SetpointKind::trapezoid, 0.02, 0.02, 0.1, 1.0};
  for (double t = 0.0; t < 0.4; t += 0.0137) {
    const double h = 1e-7;
    // Central difference on a piecewise quadratic: exact away from the phase joints; the
    // sample times avoid them, round-off ~ 1e-16/1e-7.
    EXPECT_NEAR((p.position(t + h) - p.position(t - h)) / (2 * h), p.velocity_at(t), 1e-7) << t;
  }
}

TEST(SetpointProfileTest, RejectsNonPositiveLimits) {
  EXPECT_THROW((SetpointProfile{SetpointKind::ramp, 0, 1e-3, 0.0}.validate()), std::invalid_argument);
  EXPECT_THROW((SetpointProfile{SetpointKind::trapezoid, 0, 1e-3, 0.1, -1}.validate()), std::invalid_argument);
}

// The corners are where the run's grid lands a step (scheduled_events): the step itself,
// the ramp's start and end, the trapezoid's four (three for a triangle). At each, position
// or velocity changes its law: checked against the profile's own velocity just before and
// after.
TEST(SetpointProfileTest, CornersAreWherePositionOrVelocityIsNotSmooth) {
  EXPECT_EQ((SetpointProfile{SetpointKind::step, 0.01, 1e-4}.corners()), std::vector<double>{0.01});
  const SetpointProfile ramp{SetpointKind::ramp, 0.01, -2e-3, 0.1};
  ASSERT_EQ(ramp.corners().size(), 2u);
  EXPECT_NEAR(ramp.corners()[1], 0.03, tol);
  const SetpointProfile trapezoid{SetpointKind::trapezoid, 0.0, 20e-3, 0.1, 1.0};
  const std::vector<double> c = trapezoid.corners();
  ASSERT_EQ(c.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(c[i], 0.1 * i, tol);
  const double eps = 1e-7;
  for (double t : {c[1], c[2]})  // acceleration switches: velocity continuous, slope changes
    EXPECT_NEAR(trapezoid.velocity_at(t - eps), trapezoid.velocity_at(t + eps), 1e-6);
  EXPECT_GT(trapezoid.velocity_at(c[0] + eps), 0.0);
  EXPECT_EQ(trapezoid.velocity_at(c[3] + eps), 0.0);
  // Too short to reach 0.1 m/s: a triangle, accelerate and decelerate, no cruise corner.
  const SetpointProfile triangle{SetpointKind::trapezoid, 0.0, 1e-3, 0.1, 1.0};
  ASSERT_EQ(triangle.corners().size(), 3u);
  EXPECT_NEAR(triangle.corners()[2], 2 * std::sqrt(1e-3 / 1.0), tol);
}

}  // namespace
}  // namespace mechsim::models::nc
