#include "mechsim/models/cam/force_analysis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {
namespace {

constexpr double pi = std::numbers::pi;
double rpm(double n) { return n * 2.0 * pi / 60.0; }

const CamGeometry press_geometry{0.065, 0.035, 0.0};

TEST(ForceAnalysis, ReportSpringKeepsContactAt30And60Rpm) {
  const PressCam c;
  for (double w : {rpm(30), rpm(60)}) {
    const auto n = contact_force_extremes(c.law(), press_geometry, c.follower, w);
    EXPECT_TRUE(n.contact_everywhere) << "at " << w << " rad/s";
    EXPECT_GE(n.min.contact_force_n, 0.0);
  }
}

TEST(ForceAnalysis, MinimumWithoutSpringIsWhereTheTensileLoadStarts) {
  // Without the spring the worst point is the start of the −230 N load at 100° (N jumps
  // down by 230 N there). Its value follows from the law at that angle.
  const PressCam c;
  const MotionLaw law = c.law();
  follower::FollowerParams no_spring = c.follower;
  no_spring.spring = {};
  const auto n = contact_force_extremes(law, press_geometry, no_spring, pi);
  const double at = deg_to_rad(100.0);
  const LawPoint p = law.evaluate(at);
  const double expected = (-230.0 + 25.0 * p.s_d2 * pi * pi) / std::cos(pressure_angle(p.s, p.s_d1, 0.065, 0.0));
  EXPECT_NEAR(n.min.angle_rad, at, 1e-9);  // a span start is sampled exactly (up to deg→rad rounding)
  EXPECT_NEAR(n.min.lift_m, p.s, 1e-12);
  EXPECT_NEAR(n.min.contact_force_n, expected, 1e-9);
  EXPECT_FALSE(n.contact_everywhere);
}

TEST(ForceAnalysis, MaximumIsNotBelowAnySample) {
  // Extremes are refined: a 0.01° scan (inside the load intervals) never exceeds them.
  const PressCam c;
  const MotionLaw law = c.law();
  const auto n = contact_force_extremes(law, press_geometry, c.follower, pi);
  for (int i = 0; i < 36000; ++i) {
    const double th = deg_to_rad(i * 0.01);
    const LawPoint p = law.evaluate(th);
    const auto f = follower::kinetostatic_forces(c.follower, th, p.s, p.s_d1, p.s_d2,
                                                 pressure_angle(p.s, p.s_d1, 0.065, 0.0), pi);
    // Rounding of the sum of O(500 N) terms: 1e-9 N.
    ASSERT_LE(f.contact_force_n, n.max.contact_force_n + 1e-9);
    ASSERT_GE(f.contact_force_n, n.min.contact_force_n - 1e-9);
  }
}

TEST(ForceAnalysis, MinimumSpringJustKeepsContact) {
  const PressCam c;
  for (double w : {rpm(30), rpm(60)}) {
    SCOPED_TRACE("speed " + std::to_string(w));
    const auto k = minimum_spring_stiffness(c.law(), c.follower, 125.0, w);
    ASSERT_TRUE(k.feasible);
    // The report's 9 N/mm is enough at 30 and at 60 rpm.
    EXPECT_LT(k.min_stiffness_n_per_m, 9000.0);
    follower::FollowerParams f = c.follower;
    f.spring.stiffness_n_per_m = k.min_stiffness_n_per_m;
    // At k_min the smallest N is 0 at the sizing angle (up to the ~1e-12 refinement of
    // the ratio times S ≈ 0.02 m, far below 1e-6 N); elsewhere it is larger.
    const auto at_min = contact_force_extremes(c.law(), press_geometry, f, w);
    EXPECT_NEAR(at_min.min.contact_force_n, 0.0, 1e-6);
    // 1 % less stiffness loses contact: N drops by 0.01 k S ≈ 1 N.
    f.spring.stiffness_n_per_m *= 0.99;
    EXPECT_LT(contact_force_extremes(c.law(), press_geometry, f, w).min.contact_force_n, -0.1);
  }
}

TEST(ForceAnalysis, MinimumSpringIsInfeasibleWhenThePreloadIsTooSmall) {
  // At S = 0 only the preload acts: with F0 = 100 N the −120 N load at the end of the fall
  // (S → 0 at 210°) cannot be held by any stiffness.
  const PressCam c;
  EXPECT_FALSE(minimum_spring_stiffness(c.law(), c.follower, 100.0, pi).feasible);
}

TEST(ForceAnalysis, KinetostaticLiftOffSpeedIsExact) {
  const PressCam c;
  const MotionLaw law = c.law();
  const auto lift = kinetostatic_lift_off_speed(law, c.follower);
  ASSERT_TRUE(std::isfinite(lift.speed_rad_s));
  ASSERT_GT(lift.speed_rad_s, rpm(60));  // the report's design runs at 60 rpm
  // Just below the speed N ≥ 0 everywhere, just above it N < 0: ±0.1 % of ω² changes N
  // by 0.002·m ω² |S''| ≈ 0.2 N at the critical angle, well above the refinement error.
  EXPECT_GE(contact_force_extremes(law, press_geometry, c.follower, 0.999 * lift.speed_rad_s).min.contact_force_n, 0.0);
  EXPECT_LT(contact_force_extremes(law, press_geometry, c.follower, 1.001 * lift.speed_rad_s).min.contact_force_n, 0.0);
  // At the speed and angle found, N cos α = 0 (rounding of O(300 N) terms).
  const LawPoint p = law.evaluate(lift.angle_rad);
  const auto f = follower::kinetostatic_forces(c.follower, lift.angle_rad, p.s, p.s_d1, p.s_d2, 0.0,
                                               lift.speed_rad_s);
  EXPECT_NEAR(f.normal_component_n, 0.0, 1e-9);
  EXPECT_NEAR(lift.lift_m, p.s, 1e-15);
  // Without the spring the tensile loads open the contact at rest.
  follower::FollowerParams no_spring = c.follower;
  no_spring.spring = {};
  EXPECT_EQ(kinetostatic_lift_off_speed(law, no_spring).speed_rad_s, 0.0);
}

TEST(ForceAnalysis, MeanPowerOfThePressCam) {
  const PressCam c;
  const MotionLaw law = c.law();
  const auto t = drive_torque_analysis(law, c.follower, pi);
  // The spec quotes 1.44 W (±0.005 W).
  EXPECT_NEAR(t.mean_power_w, 1.44, 0.005);
  // Exactly: the spring and the inertia do no net work; each load F over [a, b) does
  // F (S(b) − S(a)) per turn. Gauss–Legendre on 0.5° pieces of a smooth integrand is
  // accurate to rounding: 1e-12 relative.
  double work = 0.0;
  for (const auto& l : c.follower.loads) work += l.force_n * (law.evaluate(l.end_rad).s - law.evaluate(l.start_rad).s);
  EXPECT_NEAR(t.mean_power_w, work * pi / (2 * pi), 1e-12 * 1.44);
  follower::FollowerParams no_loads = c.follower;
  no_loads.loads.clear();
  EXPECT_NEAR(drive_torque_analysis(law, no_loads, pi).mean_torque_nm, 0.0, 1e-12);
}

TEST(ForceAnalysis, EnergyCurveExtremesAgreeWithTheSampledCurve) {
  const PressCam c;
  const MotionLaw law = c.law();
  const auto t = drive_torque_analysis(law, c.follower, pi);
  const auto samples = sample_cycle(law, press_geometry, c.follower, pi, 36000);
  double lo = HUGE_VAL, hi = -HUGE_VAL, at_lo = 0, at_hi = 0;
  for (const auto& s : samples) {
    if (s.a_j < lo) lo = s.a_j, at_lo = s.theta_rad;
    if (s.a_j > hi) hi = s.a_j, at_hi = s.theta_rad;
  }
  // |A'| = |M − M_mean| < 11 N m, so within 0.01° (1.75e-4 rad) of an extremum A differs
  // by < 2e-3 J; the sampled extremes cannot beat the exact ones beyond rounding.
  EXPECT_GE(lo, t.a_min_j - 1e-12);
  EXPECT_LE(hi, t.a_max_value_j + 1e-12);
  EXPECT_NEAR(lo, t.a_min_j, 2e-3);
  EXPECT_NEAR(hi, t.a_max_value_j, 2e-3);
  EXPECT_NEAR(at_lo, t.theta_a_min_rad, deg_to_rad(0.01));
  EXPECT_NEAR(at_hi, t.theta_a_max_rad, deg_to_rad(0.01));
  EXPECT_NEAR(t.a_max_j, t.a_max_value_j - t.a_min_j, 1e-15);
  // At an interior extremum the torque equals its mean (A' = 0): θ_m and θ_M of the press
  // cam lie inside smooth spans (30.1° in C1, 101.9° in C2).
  for (double th : {t.theta_a_min_rad, t.theta_a_max_rad}) {
    const LawPoint p = law.evaluate(th);
    const auto f = follower::kinetostatic_forces(c.follower, th, p.s, p.s_d1, p.s_d2, 0.0, pi);
    EXPECT_NEAR(f.drive_torque_nm, t.mean_torque_nm, 1e-9);
  }
}

TEST(ForceAnalysis, FlywheelFromTheEnergySwing) {
  const PressCam c;
  const auto t = drive_torque_analysis(c.law(), c.follower, pi);
  const auto fw = flywheel_design(t, 0.1, pi, 7800.0, 0.05);
  // I = A_max/(K ω²) and R = (2I/(π t ρ))^(1/4): a few roundings.
  EXPECT_NEAR(fw.inertia_kgm2, t.a_max_j / (0.1 * pi * pi), 1e-12);
  EXPECT_NEAR(std::pow(fw.disc_radius_m, 4) * pi * 0.05 * 7800.0 / 2.0, fw.inertia_kgm2, 1e-12);
  // Energy balance over the swing: ½ I (ω_max² − ω_min²) = A_max.
  EXPECT_NEAR(0.5 * fw.inertia_kgm2 * (fw.speed_max_rad_s * fw.speed_max_rad_s - fw.speed_min_rad_s * fw.speed_min_rad_s),
              t.a_max_j, 1e-12);
  EXPECT_NEAR((fw.speed_max_rad_s - fw.speed_min_rad_s) / pi, 0.1, 1e-15);
  // Fastest where A is smallest (the shaft has received the most energy), slowest at max A.
  EXPECT_EQ(fw.theta_speed_max_rad, t.theta_a_min_rad);
  EXPECT_EQ(fw.theta_speed_min_rad, t.theta_a_max_rad);
  EXPECT_THROW(flywheel_design(t, 0.0, pi, 7800.0, 0.05), std::invalid_argument);
}

TEST(ForceAnalysis, SampledCycleMatchesTheForceFunctions) {
  const PressCam c;
  const MotionLaw law = c.law();
  const auto samples = sample_cycle(law, press_geometry, c.follower, pi, 720);
  ASSERT_EQ(samples.size(), 720u);
  EXPECT_EQ(samples[0].a_j, 0.0);
  for (std::size_t i = 0; i < samples.size(); i += 13) {
    const auto& s = samples[i];
    const LawPoint p = law.evaluate(s.theta_rad);
    const double a = pressure_angle(p.s, p.s_d1, 0.065, 0.0);
    const auto f = follower::kinetostatic_forces(c.follower, s.theta_rad, p.s, p.s_d1, p.s_d2, a, pi);
    EXPECT_NEAR(s.contact_force_n, f.contact_force_n, 1e-9);
    EXPECT_NEAR(s.drive_torque_nm, f.drive_torque_nm, 1e-12);
    EXPECT_NEAR(s.contact_force_without_spring_n * std::cos(a), f.normal_component_n - f.spring_force_n, 1e-9);
  }
}

}  // namespace
}  // namespace mechsim::models::cam
