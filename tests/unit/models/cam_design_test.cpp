#include "mechsim/models/cam/design.h"

#include <gtest/gtest.h>

#include <numbers>

#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {
namespace {

constexpr double pi = std::numbers::pi;

CamDesignInput press_input() {
  const PressCam c;
  return {c.segments, {c.pitch_radius_m, c.roller_radius_m, 0.0}, c.speed_rad_s, c.follower};
}

// The aggregate must be the component analyses on the same inputs (compared exactly: the
// same functions on the same numbers), plus the report's headline figures.
TEST(CamDesign, PressCamReport) {
  const CamDesignInput in = press_input();
  const CamDesignReport r = analyse_cam_design(in);
  const MotionLaw law(in.segments);

  EXPECT_EQ(r.continuity.lowest_continuous_derivative, 2);
  EXPECT_EQ(r.pressure_angle.max.value, pressure_angle_extremes(law, 0.065, 0.0).max.value);
  EXPECT_TRUE(r.pressure_angle_within_limit);  // |α| ≤ 28.09° < 30°
  EXPECT_FALSE(r.curvature.undercut);
  // Spec values (quoted precision, see geometry_analysis_test).
  EXPECT_NEAR(r.optimal_eccentricity.eccentricity_m * 1e3, -3.497, 0.0005);
  EXPECT_NEAR(r.torque.mean_power_w, 1.44, 0.005);
  EXPECT_TRUE(r.contact_force.contact_everywhere);
  EXPECT_FALSE(r.contact_force_without_spring.contact_everywhere);
  EXPECT_TRUE(r.minimum_spring.feasible);
  EXPECT_EQ(r.minimum_spring.min_stiffness_n_per_m,
            minimum_spring_stiffness(law, in.follower, 125.0, pi).min_stiffness_n_per_m);
  EXPECT_EQ(r.lift_off.speed_rad_s, kinetostatic_lift_off_speed(law, in.follower).speed_rad_s);
  EXPECT_EQ(r.flywheel.inertia_kgm2, flywheel_design(r.torque, 0.1, pi, 7800.0, 0.05).inertia_kgm2);

  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.critical_event, 1u);  // the fall
  EXPECT_NEAR(r.critical_event_duration_s, 0.3889, 0.00005);  // spec: 4 decimals
  EXPECT_NEAR(r.follower_stiffness_n_per_m / 1e3, 574.19, 0.005);
  EXPECT_NEAR(r.lambda_prime, 48.24, 0.005);
  EXPECT_NEAR(r.single_rise.max_error, 6.0e-3, 0.05e-3);
  EXPECT_EQ(r.multi_rise.cycles, 20);
  EXPECT_LT(r.multi_rise.periodicity_error, 1e-12);
}

TEST(CamDesign, ChosenCriticalEventAndRefusals) {
  CamDesignInput in = press_input();
  in.critical_event = 0;  // the 93.75° rise instead
  const CamDesignReport r = analyse_cam_design(in);
  EXPECT_NEAR(r.lambda_prime, 9.38 * 360.0 / 93.75, 1e-12);
  in.critical_event = 2;
  EXPECT_THROW(analyse_cam_design(in), std::invalid_argument);
  in = press_input();
  in.segments.back().lift_m = -0.02;  // does not close
  EXPECT_THROW(analyse_cam_design(in), std::invalid_argument);
  in = press_input();
  in.geometry.eccentricity_m = 0.07;
  EXPECT_THROW(analyse_cam_design(in), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::cam
