#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/cam/press_cam.h"
#include "mechsim/models/follower/follower_block.h"

namespace mechsim::models {
namespace {

constexpr double pi = std::numbers::pi;

std::vector<std::string> input_names(const Block& b) {
  std::vector<std::string> n;
  for (const auto& p : b.inputs()) n.push_back(p.name);
  return n;
}
std::vector<std::string> output_names(const Block& b) {
  std::vector<std::string> n;
  for (const auto& p : b.outputs()) n.push_back(p.name);
  return n;
}

cam::CamShaftBlock make_cam_shaft(double e = -0.0035) {
  const cam::PressCam c;
  return cam::CamShaftBlock({c.law(), c.pitch_radius_m, e, c.speed_rad_s, 0.3});
}

TEST(CamShaftBlock, DeclaresItsPorts) {
  const cam::CamShaftBlock b = make_cam_shaft();
  // Constant speed: the angle is a function of time, not a state.
  EXPECT_EQ(b.num_states(), 0);
  EXPECT_EQ(input_names(b), (std::vector<std::string>{"load_torque", "reflected_inertia"}));
  for (const auto& in : b.inputs()) {
    EXPECT_FALSE(in.required) << in.name;
    EXPECT_EQ(in.default_value, 0.0) << in.name;
  }
  EXPECT_EQ(output_names(b),
            (std::vector<std::string>{"angle", "speed", "lift", "lift_d1", "lift_d2",
                                      "pressure_angle", "shaft_torque", "drive_power", "acceleration", "drive_load_torque", "drive_load_inertia", "kinetic_energy"}));
  for (const auto& o : b.outputs()) {
    const bool through = o.name == "shaft_torque" || o.name == "drive_power";
    EXPECT_EQ(o.feedthrough, through ? std::vector<int>{0} : std::vector<int>{}) << o.name;
  }
}

TEST(CamShaftBlock, OutputsMatchTheFreeFunctions) {
  const cam::CamShaftBlock b = make_cam_shaft();
  const cam::PressCam c;
  const cam::MotionLaw law = c.law();
  std::vector<double> y(b.num_outputs());
  for (double t : {0.0, 0.2, 0.7, 0.9, 2.8}) {  // 2.8 s: past one turn (the angle is unwrapped)
    const double theta = 0.3 + pi * t;
    b.calc_outputs(t, {}, std::vector<double>{1.5, 0.04}, y);
    const cam::LawPoint p = law.evaluate(theta);
    // Same functions on the same numbers: identical results.
    EXPECT_EQ(y[b.output_index("angle")], theta);
    EXPECT_EQ(y[b.output_index("speed")], pi);
    EXPECT_EQ(y[b.output_index("lift")], p.s);
    EXPECT_EQ(y[b.output_index("lift_d1")], p.s_d1);
    EXPECT_EQ(y[b.output_index("lift_d2")], p.s_d2);
    EXPECT_EQ(y[b.output_index("pressure_angle")], cam::pressure_angle(p.s, p.s_d1, 0.065, -0.0035));
    EXPECT_EQ(y[b.output_index("shaft_torque")], 1.5);
    EXPECT_EQ(y[b.output_index("drive_power")], 1.5 * pi);
    // Constant speed: no acceleration, so the reflected inertia takes no torque.
    EXPECT_EQ(y[b.output_index("acceleration")], 0.0);
  }
}

TEST(CamShaftBlock, RefusesBadGeometry) {
  const cam::PressCam c;
  EXPECT_THROW(cam::CamShaftBlock({c.law(), 0.065, 0.07, pi, 0.0}), std::invalid_argument);
  EXPECT_THROW(cam::CamShaftBlock({c.law(), -0.065, 0.0, pi, 0.0}), std::invalid_argument);
}

TEST(FollowerBlock, DeclaresItsPorts) {
  const cam::PressCam c;
  const follower::FollowerBlock b(c.follower);
  EXPECT_EQ(b.num_states(), 0);
  EXPECT_EQ(input_names(b), (std::vector<std::string>{"angle", "speed", "lift", "lift_d1", "lift_d2",
                                                      "pressure_angle", "acceleration"}));
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(b.inputs()[i].required) << b.inputs()[i].name;
  EXPECT_FALSE(b.inputs()[6].required);
  EXPECT_EQ(b.inputs()[6].default_value, 0.0);
  EXPECT_EQ(output_names(b),
            (std::vector<std::string>{"position", "velocity", "acceleration", "contact_force",
                                      "contact", "drive_torque", "spring_force", "load_force",
                                      "inertia_force", "drive_torque_rest", "reflected_inertia",
                                      "lift_off_count", "load_power", "kinetic_energy", "spring_energy"}));
  // Every output but the (constant) lift-off count depends directly on some input (the
  // block has no state).
  for (const auto& o : b.outputs())
    EXPECT_EQ(o.feedthrough.empty(), o.name == "lift_off_count") << o.name;
  // What a dynamic cam shaft reads must not depend on its acceleration (input 6): that
  // would close an algebraic loop across the cut.
  for (const char* name : {"drive_torque_rest", "reflected_inertia"})
    for (int i : b.outputs()[b.output_index(name)].feedthrough) EXPECT_NE(i, 6) << name;
  // The cam outputs connect to the follower inputs by name.
  const cam::CamShaftBlock shaft = make_cam_shaft();
  for (int i = 0; i < 6; ++i) EXPECT_GE(shaft.output_index(b.inputs()[i].name), 0);
}

TEST(FollowerBlock, OutputsMatchTheFreeFunctions) {
  const cam::PressCam c;
  const follower::FollowerBlock b(c.follower);
  const cam::MotionLaw law = c.law();
  std::vector<double> y(b.num_outputs());
  for (double theta : {0.5, 1.8, 2.0, 3.3, 2 * pi + 3.3}) {
    const cam::LawPoint p = law.evaluate(theta);
    const double a = cam::pressure_angle(p.s, p.s_d1, 0.065, 0.0), w = 2 * pi, wd = -0.7;
    b.calc_outputs(0.0, {}, std::vector<double>{theta, w, p.s, p.s_d1, p.s_d2, a, wd}, y);
    const auto f = follower::kinetostatic_forces(c.follower, theta, p.s, p.s_d1, p.s_d2, a, w, wd);
    EXPECT_EQ(y[b.output_index("position")], p.s);
    EXPECT_EQ(y[b.output_index("velocity")], p.s_d1 * w);
    EXPECT_EQ(y[b.output_index("acceleration")], p.s_d2 * w * w + p.s_d1 * wd);
    EXPECT_EQ(y[b.output_index("contact_force")], f.contact_force_n);
    EXPECT_EQ(y[b.output_index("contact")], f.contact_force_n >= 0 ? 1.0 : 0.0);
    EXPECT_EQ(y[b.output_index("drive_torque")], f.drive_torque_nm);
    EXPECT_EQ(y[b.output_index("spring_force")], f.spring_force_n);
    EXPECT_EQ(y[b.output_index("load_force")], f.functional_load_n);
    EXPECT_EQ(y[b.output_index("inertia_force")], f.inertia_force_n);
    EXPECT_EQ(y[b.output_index("drive_torque_rest")], f.drive_torque_rest_nm);
    EXPECT_EQ(y[b.output_index("reflected_inertia")], follower::reflected_inertia(c.follower.mass, p.s_d1));
    // The split is exact: full torque = rest + m S'² ω̇ (up to rounding of ~1e-15 N m).
    EXPECT_NEAR(y[b.output_index("drive_torque")],
                y[b.output_index("drive_torque_rest")] + y[b.output_index("reflected_inertia")] * wd, 1e-12);
  }
  // Functional loads at the wrapped angle: 190° + 360° lies in the tensile 180–210° load.
  const double th = cam::deg_to_rad(190.0) + 2 * pi;
  b.calc_outputs(0.0, {}, std::vector<double>{th, pi, 0.0, 0.0, 0.0, 0.0, 0.0}, y);
  EXPECT_EQ(y[b.output_index("load_force")], -120.0);
  // Contact flag: a large negative inertia force opens the contact.
  b.calc_outputs(0.0, {}, std::vector<double>{0.0, 100.0, 0.0, 0.0, -1.0, 0.0, 0.0}, y);
  EXPECT_LT(y[b.output_index("contact_force")], 0.0);
  EXPECT_EQ(y[b.output_index("contact")], 0.0);
}

}  // namespace
}  // namespace mechsim::models
