// The flexible follower block by hand (no integrator): ports, the static start, the
// equation of motion, and the contact mode switched by its event functions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/models/cam/press_cam.h"
#include "mechsim/models/follower/flexible_follower_block.h"
#include "mechsim/models/follower/follower_block.h"

namespace mechsim::models::follower {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double kf = 574190.0;  // N/m, the report's follower stiffness

FlexibleFollowerParams press_follower(double contact_damping, double frame_damping = 0.0) {
  return {cam::PressCam{}.follower, {kf, contact_damping, frame_damping}, 0.0};
}

// Inputs in port order: angle, speed, lift, lift_d1, lift_d2, pressure_angle, acceleration.
std::vector<double> inputs(double angle, double speed, double lift, double lift_d1, double alpha = 0.0) {
  return {angle, speed, lift, lift_d1, 0.0, alpha, 0.0};
}

double output(const Block& b, std::span<const double> x, std::span<const double> u, const char* name) {
  std::vector<double> y(b.num_outputs());
  b.calc_outputs(0.0, x, u, y);
  return y[b.output_index(name)];
}

TEST(FlexibleFollowerBlock, PortsMatchTheRigidFollower) {
  const FlexibleFollowerBlock b(press_follower(600.0));
  const FollowerBlock rigid(cam::PressCam{}.follower);
  // Same node type, same topic: every input and output of the rigid follower exists here.
  for (const auto& in : rigid.inputs()) EXPECT_GE(b.input_index(in.name), 0) << in.name;
  for (const auto& out : rigid.outputs()) EXPECT_GE(b.output_index(out.name), 0) << out.name;
  // The deflection δ = S − y, not y, is the state: the contact force k_f δ stays resolved
  // by the solver's error control however stiff the follower (docs/cam-dynamics.md).
  EXPECT_EQ(b.state_names(), (std::vector<std::string>{"deflection", "velocity"}));
  EXPECT_EQ(b.num_event_functions(), 2);
  EXPECT_EQ(b.event_direction(0), Crossing::falling);  // lift-off
  EXPECT_EQ(b.event_direction(1), Crossing::rising);   // landing
  // No output depends on the shaft's acceleration: no loop with a dynamic shaft.
  const int accel = b.input_index("acceleration");
  for (const auto& o : b.outputs())
    for (int i : o.feedthrough) EXPECT_NE(i, accel) << o.name;
}

TEST(FlexibleFollowerBlock, StartsAtRestInStaticEquilibrium) {
  const FlexibleFollowerBlock b(press_follower(600.0, 50.0));
  std::vector<double> x(2), dxdt(2);
  b.initial_state(0.0, x);
  // k_f (0 − y) = F0 + k y on the base circle: y = −F0/(k_f + k), δ = −y.
  EXPECT_DOUBLE_EQ(x[0], 125.0 / (kf + 9000.0));
  EXPECT_EQ(x[1], 0.0);
  const auto u = inputs(0.1, pi, 0.0, 0.0);  // a dwell without load
  b.derivatives(0.0, x, u, dxdt);
  EXPECT_EQ(dxdt[0], 0.0);
  EXPECT_NEAR(dxdt[1], 0.0, 1e-12);  // rounding of forces of ~1e2 N over 25 kg
  EXPECT_NEAR(output(b, x, u, "contact_force"), 125.0 * kf / (kf + 9000.0), 1e-9);
}

TEST(FlexibleFollowerBlock, EquationOfMotionAndOutputs) {
  const double cf = 600.0, c = 40.0;
  const FlexibleFollowerBlock b(press_follower(cf, c));
  const double theta = 60.0 * pi / 180.0;  // in the +100 N load
  const double s = 0.010, s1 = 0.02, w = 2.0, alpha = 0.3;
  const double y = 0.0095, v = 0.03;
  const std::vector<double> x{s - y, v};  // deflection, velocity
  const auto u = inputs(theta, w, s, s1, alpha);
  const double f = kf * (s - y) + cf * (s1 * w - v);  // axial contact force
  const double a = (f - 100.0 - (125.0 + 9000.0 * y) - c * v) / 25.0;
  std::vector<double> dxdt(2);
  b.derivatives(0.0, x, u, dxdt);
  EXPECT_EQ(dxdt[0], s1 * w - v);  // δ̇ = Ṡ − ẏ
  EXPECT_NEAR(dxdt[1], a, 1e-12 * std::abs(f) / 25.0);
  EXPECT_NEAR(output(b, x, u, "contact_force"), f / std::cos(alpha), 1e-12 * f);
  EXPECT_NEAR(output(b, x, u, "drive_torque"), f * s1, 1e-12 * f);  // P = F Ṡ = (F S') ω
  EXPECT_EQ(output(b, x, u, "drive_torque_rest"), output(b, x, u, "drive_torque"));
  EXPECT_EQ(output(b, x, u, "reflected_inertia"), 0.0);
  EXPECT_EQ(output(b, x, u, "load_force"), 100.0);
  EXPECT_DOUBLE_EQ(output(b, x, u, "deflection"), s - y);
  EXPECT_DOUBLE_EQ(output(b, x, u, "position"), y);
  EXPECT_DOUBLE_EQ(output(b, x, u, "velocity"), v);
  EXPECT_EQ(output(b, x, u, "contact"), 1.0);
}

TEST(FlexibleFollowerBlock, LiftOffAndLandingSwitchTheModeAndAreLogged) {
  const double cf = 600.0;
  FlexibleFollowerBlock b(press_follower(cf));
  std::vector<double> x(2), g(2);
  b.initial_state(0.0, x);
  ASSERT_TRUE(b.in_contact());
  // Contact: g[0] is the contact function h = min(k_f δ, F), here F (the damper pulls).
  x = {0.0001, 0.5};
  const auto u = inputs(3.0, pi, 0.0011, -0.01);
  b.event_functions(0.0, x, u, g);
  const double spring = kf * 0.0001, force = spring + cf * (-0.01 * pi - 0.5);
  EXPECT_DOUBLE_EQ(g[0], std::min(spring, force));
  EXPECT_LT(g[1], 0.0);  // landing function inactive in contact

  const std::vector<int> lift_off{-1, 0};
  EXPECT_TRUE(b.handle_events(0.7, x, u, lift_off));
  EXPECT_FALSE(b.in_contact());
  EXPECT_EQ(output(b, x, u, "contact_force"), 0.0);  // flying: nothing pushes
  EXPECT_EQ(output(b, x, u, "contact"), 0.0);
  EXPECT_EQ(output(b, x, u, "lift_off_count"), 1.0);
  b.event_functions(0.0, x, u, g);
  EXPECT_GT(g[0], 0.0);  // lift-off function inactive while flying
  EXPECT_DOUBLE_EQ(g[1], std::min(spring, force));
  // A repeated lift-off crossing while flying changes nothing.
  EXPECT_FALSE(b.handle_events(0.71, x, u, lift_off));

  std::vector<double> x_land{0.0, -0.2};
  const auto u_land = inputs(3.5, pi, 0.002, -0.01);
  EXPECT_TRUE(b.handle_events(0.75, x_land, u_land, std::vector<int>{0, 1}));
  EXPECT_TRUE(b.in_contact());

  const auto log = b.take_event_log();
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0].kind, "lift_off");
  EXPECT_EQ(log[0].t, 0.7);
  ASSERT_EQ(log[0].values.size(), 1u);
  EXPECT_EQ(log[0].values[0].first, "angle_deg");
  EXPECT_NEAR(log[0].values[0].second, 3.0 * 180.0 / pi, 1e-12);
  EXPECT_EQ(log[1].kind, "landing");
  ASSERT_EQ(log[1].values.size(), 3u);
  EXPECT_EQ(log[1].values[1].first, "flight_duration_s");
  EXPECT_NEAR(log[1].values[1].second, 0.05, 1e-15);
  EXPECT_EQ(log[1].values[2].first, "impact_velocity_m_per_s");
  EXPECT_DOUBLE_EQ(log[1].values[2].second, -0.01 * pi + 0.2);  // Ṡ − ẏ
  EXPECT_TRUE(b.take_event_log().empty());  // taken once
}

TEST(FlexibleFollowerBlock, ModeIsPartOfTheSavedStateAndResetAtTheStart) {
  FlexibleFollowerBlock b(press_follower(0.0));
  std::vector<double> x(2);
  b.initial_state(0.0, x);
  const auto u = inputs(0.0, pi, 0.0, 0.0);
  b.handle_events(0.2, x, u, std::vector<int>{-1, 0});
  const auto saved = b.save_discrete_state();
  b.handle_events(0.3, x, u, std::vector<int>{0, 1});
  ASSERT_TRUE(b.in_contact());
  b.restore_discrete_state(saved);
  EXPECT_FALSE(b.in_contact());
  EXPECT_EQ(b.lift_off_count(), 1);
  b.initial_state(0.0, x);  // a new run starts in contact, nothing counted
  EXPECT_TRUE(b.in_contact());
  EXPECT_EQ(b.lift_off_count(), 0);
  EXPECT_TRUE(b.take_event_log().empty());
}

TEST(FlexibleFollowerBlock, RefusesNonPhysicalParameters) {
  EXPECT_THROW(FlexibleFollowerBlock(press_follower(-1.0)), std::invalid_argument);
  auto p = press_follower(0.0);
  p.contact.stiffness_n_per_m = 0.0;
  EXPECT_THROW(FlexibleFollowerBlock{p}, std::invalid_argument);
  p = press_follower(0.0);
  p.follower.mass = 0.0;
  EXPECT_THROW(FlexibleFollowerBlock{p}, std::invalid_argument);
  // c = 2ζ√(k m): the report's ζ = 0.08 on 574.19 N/mm and 25 kg is 606.3 N s/m.
  EXPECT_NEAR(damping_for_ratio(0.08, kf, 25.0), 606.20, 0.005);
}

}  // namespace
}  // namespace mechsim::models::follower
