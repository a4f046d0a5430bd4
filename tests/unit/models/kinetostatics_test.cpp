#include "mechsim/models/follower/kinetostatics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models {
namespace {

using cam::deg_to_rad;
constexpr double pi = std::numbers::pi;

double rpm(double n) { return n * 2.0 * pi / 60.0; }

// Smallest N over one cycle, sampled every 0.01°. The loads switch at whole degrees and
// the joints of the law lie on the 0.01° grid, so every interval is sampled at its left
// end; between samples N is smooth and varies by < 0.1 N per 0.01°.
double min_contact_force(const cam::PressCam& c, double omega) {
  const cam::MotionLaw law = c.law();
  double lowest = HUGE_VAL;
  for (int i = 0; i < 36000; ++i) {
    const double th = deg_to_rad(i * 0.01);
    const cam::LawPoint p = law.evaluate(th);
    const double a = cam::pressure_angle(p.s, p.s_d1, c.pitch_radius_m, c.eccentricity_m);
    lowest = std::min(lowest, follower::kinetostatic_forces(c.follower, th, p.s, p.s_d1, p.s_d2, a,
                                                            omega).contact_force_n);
  }
  return lowest;
}

TEST(Kinetostatics, ReportSpringKeepsContactAt30And60Rpm) {
  const cam::PressCam c;  // k = 9 N/mm, F0 = 125 N
  // The report's verdict is N ≥ 0 everywhere; the sampled minimum stays well above the
  // < 0.1 N sampling error, so the strict check is meaningful.
  EXPECT_GT(min_contact_force(c, rpm(30)), 0.1);
  EXPECT_GT(min_contact_force(c, rpm(60)), 0.1);
  // Without the spring the tensile loads pull the follower off the cam (spec §3).
  cam::PressCam no_spring;
  no_spring.follower.spring = {};
  EXPECT_LT(min_contact_force(no_spring, rpm(30)), -0.1);
}

TEST(Kinetostatics, LiftOffAtAMuchHigherSpeed) {
  const cam::PressCam c;
  // Inertia grows with ω²: at 300 rpm (100× the 30 rpm inertia force) the fall's
  // deceleration pulls the follower off the cam.
  EXPECT_LT(min_contact_force(c, rpm(300)), -0.1);
}

TEST(Kinetostatics, ForceBalanceTerms) {
  follower::FollowerParams p{25.0, {9000.0, 125.0}, cam::press_cam_loads()};
  const double s = 0.012, s1 = 0.02, s2 = -0.05, alpha = 0.3, w = pi, wd = 2.0;
  const auto f = follower::kinetostatic_forces(p, deg_to_rad(100.0), s, s1, s2, alpha, w, wd);
  // Exact arithmetic on a few terms: rounding < 1e-12 N.
  EXPECT_NEAR(f.functional_load_n, -230.0, 1e-12);  // [100°, 120°) includes 100°
  EXPECT_NEAR(f.spring_force_n, 125.0 + 9000.0 * s, 1e-12);
  EXPECT_NEAR(f.inertia_force_n, 25.0 * (s2 * w * w + s1 * wd), 1e-12);
  EXPECT_NEAR(f.normal_component_n, f.functional_load_n + f.spring_force_n + f.inertia_force_n, 1e-12);
  EXPECT_NEAR(f.contact_force_n * std::cos(alpha), f.normal_component_n, 1e-12);
  EXPECT_NEAR(f.drive_torque_nm, f.normal_component_n * s1, 1e-12);
}

TEST(Kinetostatics, ReflectedInertiaCarriesTheAccelerationTorque) {
  // The ω̇ part of the drive torque is m S' ω̇ · S' = (m S'²) ω̇ (rounding only).
  follower::FollowerParams p{25.0, {}, {}};
  const double s1 = 0.03, wd = 4.0;
  const auto with = follower::kinetostatic_forces(p, 1.0, 0.01, s1, 0.0, 0.2, pi, wd);
  const auto without = follower::kinetostatic_forces(p, 1.0, 0.01, s1, 0.0, 0.2, pi, 0.0);
  EXPECT_NEAR(with.drive_torque_nm - without.drive_torque_nm, follower::reflected_inertia(25.0, s1) * wd, 1e-15);
}

TEST(Kinetostatics, FunctionalLoadsAreHalfOpenAndPeriodic) {
  const auto loads = cam::press_cam_loads();
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(44.999)), 0.0);
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(45.0)), 100.0);
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(99.999)), 100.0);
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(100.0)), -230.0);
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(120.0)), 0.0);
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(190.0) + 2 * pi), -120.0);
  EXPECT_EQ(follower::functional_load(loads, deg_to_rad(190.0) - 4 * pi), -120.0);
}

TEST(Kinetostatics, ValidationRefusesBadParameters) {
  EXPECT_THROW(follower::validate({-1.0, {}, {}}), std::invalid_argument);
  EXPECT_THROW(follower::validate({1.0, {-5.0, 0.0}, {}}), std::invalid_argument);
  EXPECT_THROW(follower::validate({1.0, {}, {{1.0, 0.5, 10.0}}}), std::invalid_argument);
  EXPECT_THROW(follower::validate({1.0, {}, {{0.0, 1.0, 10.0}, {0.5, 2.0, 5.0}}}),
               std::invalid_argument);
  EXPECT_NO_THROW(follower::validate({25.0, {9000.0, 125.0}, cam::press_cam_loads()}));
}

}  // namespace
}  // namespace mechsim::models
