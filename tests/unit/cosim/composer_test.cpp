// The monolithic composer wires the same blocks into one ODE; checked against the
// closed-form kinetostatics of the cam press (constant speed: theta = omega t).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechsim/cosim/composer.h"
#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/cam/press_cam.h"
#include "mechsim/models/follower/kinetostatics.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

TEST(Composer, ReferenceOfTheCamPressMatchesTheClosedFormKinetostatics) {
  config::Scene scene = config::load_scene(testing::shipped_scene("cam_press.yaml"));
  ScenePlan plan = ScenePlan::build(scene);
  ReferenceRun ref = run_reference(plan);
  models::cam::PressCam press;
  const auto law = press.law();
  const auto& t = ref.log.data[0];
  const auto& n = ref.log.data[ref.log.column("follower.contact_force")];
  const auto& m_shaft = ref.log.data[ref.log.column("cam.shaft_torque")];
  const auto& m_drive = ref.log.data[ref.log.column("follower.drive_torque")];
  ASSERT_EQ(t.size(), 2004u);  // 2000 steps of 1 ms, 3 landed on load boundaries off the grid
  double worst = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double theta = press.speed_rad_s * t[k];
    const auto p = law.evaluate(theta);
    const double alpha = models::cam::pressure_angle(p.s, p.s_d1, press.pitch_radius_m, press.eccentricity_m);
    const auto f = models::follower::kinetostatic_forces(press.follower, theta, p.s, p.s_d1, p.s_d2, alpha,
                                                         press.speed_rad_s);
    worst = std::max(worst, std::abs(n[k] - f.contact_force_n));
    // The composer evaluates the feedthrough chain follower -> cam in one pass: no lag.
    ASSERT_EQ(m_shaft[k], m_drive[k]) << "step " << k;
  }
  // The composite evaluates the same functions on the same angle: only the order of
  // floating-point operations could differ, far below 1e-9 of forces of ~1e3 N; a wrong
  // wire (an input fed from the wrong output) would be off by newtons.
  EXPECT_LT(worst, 1e-9 * 1e3);
}

}  // namespace
}  // namespace mechsim::cosim
