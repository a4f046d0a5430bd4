// A cam shaft driven through an elastic line-shaft segment (drive: shaft_segment,
// docs/line-shaft.md) and a geared shaft handing a downstream segment's torque back:
// ports, the equations (I + J_r) ω̇ = k q + c q̇ − M_rest − T_down, q̇ = ω_u − ω, the segment's energy
// outputs, and the energy balance of a shaft wound up against a load.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {
namespace {

constexpr double k_seg = 2e5, c_seg = 200.0, inertia = 20.0;

CamShaftParams segment_driven(double stiffness = k_seg, double damping = c_seg) {
  const PressCam c;
  CamShaftParams p{c.law(), c.pitch_radius_m, 0.0, std::numbers::pi, 0.0};
  p.segment = ShaftSegment{stiffness, damping};
  p.inertia_kgm2 = inertia;
  p.initial_speed = 9.8;
  return p;
}

TEST(LineShaftSegment, DeclaresStatesAndRequiredUpstreamInputs) {
  const CamShaftBlock b(segment_driven());
  EXPECT_TRUE(b.is_segment_driven());
  EXPECT_EQ(b.state_names(), (std::vector<std::string>{"angle", "speed", "twist"}));
  const int speed = b.input_index("drive_speed"), down = b.input_index("downstream_torque");
  EXPECT_EQ(b.input_index("drive_angle"), -1);  // the twist is integrated from the speeds
  ASSERT_GE(speed, 0);
  ASSERT_GE(down, 0);
  EXPECT_TRUE(b.inputs()[speed].required);
  EXPECT_FALSE(b.inputs()[down].required);
  EXPECT_EQ(b.inputs()[down].default_value, 0.0);
  // Angle and speed are states: nothing reaches them directly, so neighbours on the line
  // shaft can read each other both ways without an algebraic loop.
  EXPECT_TRUE(b.outputs()[b.output_index("angle")].feedthrough.empty());
  EXPECT_TRUE(b.outputs()[b.output_index("speed")].feedthrough.empty());
  EXPECT_EQ(b.outputs()[b.output_index("drive_load_torque")].feedthrough, (std::vector<int>{speed}));
  std::vector<double> x(3, -1.0);
  b.initial_state(0.0, x);
  EXPECT_EQ(x[0], 0.0);
  EXPECT_EQ(x[1], 9.8);
  EXPECT_EQ(x[2], 0.0);  // untwisted at the start
}

TEST(LineShaftSegment, EquationAndOutputs) {
  const CamShaftBlock b(segment_driven());
  std::vector<double> u(b.num_inputs(), 0.0), x{1.0, 9.0, 0.002}, dxdt(3), y(b.num_outputs());
  u[b.input_index("load_torque")] = 300.0;
  u[b.input_index("reflected_inertia")] = 0.5;
  u[b.input_index("drive_speed")] = 9.1;  // twist rate 0.1 rad/s
  u[b.input_index("downstream_torque")] = 50.0;
  const double torque = k_seg * 0.002 + c_seg * 0.1;  // 420 N m, up to the rounding of 9.1 - 9
  b.derivatives(0.0, x, u, dxdt);
  EXPECT_EQ(dxdt[0], 9.0);
  EXPECT_NEAR(dxdt[1], (torque - 300.0 - 50.0) / 20.5, 1e-9);
  EXPECT_NEAR(dxdt[2], 0.1, 1e-12);
  b.calc_outputs(3.0, x, u, y);
  EXPECT_EQ(y[b.output_index("angle")], 1.0);
  EXPECT_EQ(y[b.output_index("speed")], 9.0);
  EXPECT_EQ(y[b.output_index("acceleration")], dxdt[1]);
  EXPECT_NEAR(y[b.output_index("shaft_torque")], torque, 1e-9);
  EXPECT_EQ(y[b.output_index("drive_load_torque")], y[b.output_index("shaft_torque")]);  // action = reaction
  EXPECT_EQ(y[b.output_index("drive_load_inertia")], 0.0);  // the shaft carries its own inertia
  EXPECT_NEAR(y[b.output_index("segment_energy")], 0.5 * k_seg * 0.002 * 0.002, 1e-12);
  EXPECT_NEAR(y[b.output_index("segment_damping_power")], c_seg * 0.01, 1e-10);
  EXPECT_DOUBLE_EQ(y[b.output_index("kinetic_energy")], 0.5 * 20.0 * 81.0);
}

TEST(LineShaftSegment, RefusesInconsistentDrives) {
  EXPECT_THROW(CamShaftBlock(segment_driven(0.0)), std::invalid_argument);
  EXPECT_THROW(CamShaftBlock(segment_driven(k_seg, -1.0)), std::invalid_argument);
  CamShaftParams no_inertia = segment_driven();
  no_inertia.inertia_kgm2 = 0.0;
  EXPECT_THROW(CamShaftBlock{no_inertia}, std::invalid_argument);
  CamShaftParams geared = segment_driven();
  geared.gear_ratio = 10.0;
  EXPECT_THROW(CamShaftBlock{geared}, std::invalid_argument);
  CamShaftParams torque_driven = segment_driven();
  torque_driven.drive.type = DriveType::constant_torque;
  torque_driven.drive.torque_nm = 1.0;
  EXPECT_THROW(CamShaftBlock{torque_driven}, std::invalid_argument);
}

// A geared station hands the downstream segment's torque back through the gear with the
// follower's: the driving shaft carries both.
TEST(LineShaftSegment, GearHandsTheDownstreamTorqueBack) {
  const PressCam c;
  CamShaftParams p{c.law(), c.pitch_radius_m, 0.0, 0.0, 0.0};
  p.gear_ratio = 10.0;
  p.inertia_kgm2 = 252.0;
  const CamShaftBlock b(p);
  std::vector<double> u(b.num_inputs(), 0.0), x{0.5}, y(b.num_outputs());
  u[b.input_index("load_torque")] = 1000.0;
  u[b.input_index("reflected_inertia")] = 0.2;
  u[b.input_index("drive_speed")] = 98.0;
  u[b.input_index("drive_acceleration")] = 5.0;
  u[b.input_index("downstream_torque")] = 400.0;
  b.calc_outputs(0.0, x, u, y);
  EXPECT_DOUBLE_EQ(y[b.output_index("drive_load_torque")], 140.0);  // (1000 + 400) / 10
  EXPECT_DOUBLE_EQ(y[b.output_index("shaft_torque")], 1400.0 + 252.2 * 0.5);
  EXPECT_DOUBLE_EQ(y[b.output_index("drive_load_inertia")], 252.2 / 100.0);
}

// The upstream end turns at a constant 10 rad/s; the station starts at rest against a
// constant load M, so the segment winds up and the station settles at the upstream speed with
// the twist M/k. Integrated here with classical RK4 at 10 µs (error ~(ω h)^4 of a 100 rad/s
// mode: 1e-12 of the energies), the work put in at the upstream end, ∫ T ω_u dt, equals the
// load work ∫ M ω dt, the damper's ∫ c q̇² dt and the final kinetic and elastic energy.
TEST(LineShaftSegment, WindUpClosesTheEnergyBalance) {
  const CamShaftBlock b(segment_driven());
  const double omega_u = 10.0, load = 2000.0, h = 1e-5, t_end = 1.5;
  std::vector<double> u(b.num_inputs(), 0.0), x{0.0, 0.0, 0.0}, y(b.num_outputs());
  u[b.input_index("load_torque")] = load;
  const auto inputs_at = [&](double) { u[b.input_index("drive_speed")] = omega_u; };
  // Input power, load power and damper power at (t, state).
  const auto powers = [&](double t, const std::vector<double>& state) {
    inputs_at(t);
    b.calc_outputs(t, state, u, y);
    const double T = y[b.output_index("shaft_torque")];
    return std::vector<double>{T * omega_u, load * state[1], y[b.output_index("segment_damping_power")]};
  };
  const auto f = [&](double t, const std::vector<double>& state) {
    inputs_at(t);
    std::vector<double> d(3);
    b.derivatives(t, state, u, d);
    return d;
  };
  std::vector<double> work(3, 0.0);
  for (double t = 0.0; t < t_end - h / 2; t += h) {
    const auto k1 = f(t, x);
    const auto stage = [&](const std::vector<double>& k, double a) {
      return std::vector<double>{x[0] + a * k[0], x[1] + a * k[1], x[2] + a * k[2]};
    };
    const auto k2 = f(t + h / 2, stage(k1, h / 2));
    const auto k3 = f(t + h / 2, stage(k2, h / 2));
    const auto k4 = f(t + h, stage(k3, h));
    std::vector<double> next(3);
    for (int i = 0; i < 3; ++i) next[i] = x[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    // Trapezoidal power integral on the fine grid (error ~h² P'' T / 12: ~1e-9 of the work).
    const auto p0 = powers(t, x), p1 = powers(t + h, next);
    for (int i = 0; i < 3; ++i) work[i] += h / 2 * (p0[i] + p1[i]);
    x = next;
  }
  inputs_at(t_end);
  b.calc_outputs(t_end, x, u, y);
  // Settled (damping ratio c / (2 sqrt(k I)) = 0.05 of a 100 rad/s mode: e^-7.5 after 1.5 s).
  EXPECT_NEAR(x[1], omega_u, 1e-2);
  EXPECT_NEAR(x[2], load / k_seg, 1e-3 * load / k_seg + 1e-4);
  // The twist state is the angle difference: the speeds it integrates are the angles' rates.
  EXPECT_NEAR(omega_u * t_end - x[0], x[2], 1e-9);
  const double stored = y[b.output_index("kinetic_energy")] + y[b.output_index("segment_energy")];
  const double balance = work[0] - work[1] - work[2] - stored;
  EXPECT_GT(work[2], 0.0);
  EXPECT_LT(std::abs(balance), 1e-6 * work[0]) << "input " << work[0] << " load " << work[1] << " damper " << work[2]
                                               << " stored " << stored;
}

}  // namespace
}  // namespace mechsim::models::cam
