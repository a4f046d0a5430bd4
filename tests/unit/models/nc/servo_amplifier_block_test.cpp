// ServoAmplifierBlock (spec nc_slide.md §3).
#include "mechsim/models/nc/servo_amplifier_block.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

namespace mechsim::models::nc {
namespace {

constexpr double radians_per_metre = 2 * std::numbers::pi / 0.005;
// The law is a handful of products and sums: compare to 1e-12 of the volts involved.
constexpr double tol = 1e-12 * 100;

struct Io {
  std::vector<double> x, u, y, dx;
};
Io make_io(const Block& b) {
  return {std::vector<double>(b.num_states(), 0.0), b.default_inputs(), std::vector<double>(b.num_outputs()),
          std::vector<double>(b.num_states())};
}

TEST(ServoAmplifierBlockTest, TopologyContinuous) {
  const ServoAmplifierBlock dut;
  ASSERT_EQ(dut.num_inputs(), 2);
  EXPECT_TRUE(dut.inputs()[dut.input_index("tacho_voltage")].required);
  EXPECT_TRUE(dut.inputs()[dut.input_index("spindle_angle")].required);
  EXPECT_EQ(dut.input_index("position_setpoint"), -1);
  EXPECT_EQ(dut.state_names(), (std::vector<std::string>{"integrator", "filtered_tacho_voltage"}));
  // The spindle angle reaches the voltage directly (proportional path); the tacho voltage
  // only through its filter.
  EXPECT_EQ(dut.outputs()[dut.output_index("armature_voltage")].feedthrough,
            std::vector<int>{dut.input_index("spindle_angle")});
  EXPECT_TRUE(dut.outputs()[dut.output_index("position_reference")].feedthrough.empty());
  EXPECT_GE(dut.output_index("velocity_error"), 0);
  EXPECT_GE(dut.output_index("saturated"), 0);
}

TEST(ServoAmplifierBlockTest, TopologyExternalSampledAndCurrentLimited) {
  ServoAmplifierParams p;
  p.setpoint_source = SetpointSource::external;
  p.current_limit.enabled = true;
  const ServoAmplifierBlock external(p);
  const int sp = external.input_index("position_setpoint");
  ASSERT_GE(sp, 0);
  EXPECT_TRUE(external.inputs()[sp].required);
  auto ft = external.outputs()[external.output_index("armature_voltage")].feedthrough;
  std::sort(ft.begin(), ft.end());
  EXPECT_EQ(ft.size(), 3u);  // setpoint, spindle angle and (for the clamp) the tacho voltage
  p.sample_time = 1e-3;
  const ServoAmplifierBlock sampled(p);
  for (const auto& out : sampled.outputs()) EXPECT_TRUE(out.feedthrough.empty()) << out.name;
  EXPECT_EQ(sampled.sample_time(), 1e-3);
}

TEST(ServoAmplifierBlockTest, ContinuousLawByHand) {
  const ServoAmplifierBlock dut;  // step of 0.1 mm at t = 0
  Io io = make_io(dut);
  io.x = {1.0, 2.0};  // z, U_Tf
  io.u[dut.input_index("tacho_voltage")] = 2.5;
  io.u[dut.input_index("spindle_angle")] = 0.1;
  dut.calc_outputs(0.0, io.x, io.u, io.y);
  dut.derivatives(0.0, io.x, io.u, io.dx);
  const double e = 0.0496 * 40 * (1e-4 * radians_per_metre - 0.1) - 2.0;
  const double voltage = 10 * e + 1.0;  // unsaturated here
  EXPECT_NEAR(io.y[dut.output_index("velocity_error")], e, tol);
  EXPECT_NEAR(io.y[dut.output_index("armature_voltage")], voltage, tol);
  EXPECT_EQ(io.y[dut.output_index("saturated")], 0.0);
  EXPECT_NEAR(io.y[dut.output_index("position_reference")], 1e-4, 1e-18);
  EXPECT_NEAR(io.dx[0], 10 / 0.01 * e, tol * 1e3);
  EXPECT_NEAR(io.dx[1], (2.5 - 2.0) / 0.3e-3, tol * 1e4);
}

TEST(ServoAmplifierBlockTest, SaturationBacksTheIntegratorOff) {
  ServoAmplifierParams p;
  p.setpoint.distance = 5e-3;
  const ServoAmplifierBlock dut(p);
  Io io = make_io(dut);
  dut.calc_outputs(0.0, io.x, io.u, io.y);
  dut.derivatives(0.0, io.x, io.u, io.dx);
  const double e = 0.0496 * 40 * 5e-3 * radians_per_metre;
  const double u = 10 * e;
  EXPECT_EQ(io.y[dut.output_index("armature_voltage")], 50.0);
  EXPECT_EQ(io.y[dut.output_index("saturated")], 1.0);
  // dz/dt = (K_sv/T_i) e + (U_a − u)/T_t
  EXPECT_NEAR(io.dx[0], 1000 * e + (50.0 - u) / 5e-3, 1e-9 * 1000 * e);
  // Mirror image for a negative step.
  p.setpoint.distance = -5e-3;
  const ServoAmplifierBlock negative(p);
  negative.calc_outputs(0.0, io.x, io.u, io.y);
  EXPECT_EQ(io.y[negative.output_index("armature_voltage")], -50.0);
}

TEST(ServoAmplifierBlockTest, CurrentLimitClampsAroundTheBackEmf) {
  ServoAmplifierParams p;
  p.setpoint.distance = 5e-3;
  p.current_limit.enabled = true;
  const ServoAmplifierBlock dut(p);
  Io io = make_io(dut);
  io.u[dut.input_index("tacho_voltage")] = 2.48;  // ω2 = 50 rad/s: back-emf 10 V
  dut.calc_outputs(0.0, io.x, io.u, io.y);
  // Upper clamp E + R_a I_max = 10 + 0.27921 · 30: the current it drives at this speed is
  // exactly 30 A in steady state.
  EXPECT_NEAR(io.y[dut.output_index("armature_voltage")], 10.0 + 0.27921 * 30, 1e-12);
  EXPECT_EQ(io.y[dut.output_index("saturated")], 1.0);
}

TEST(ServoAmplifierBlockTest, VelocityFeedForwardAddsTheReferenceSpeed) {
  ServoAmplifierParams p;
  p.setpoint = {SetpointKind::trapezoid, 0.0, 0.02, 0.1, 1.0};
  p.velocity_feedforward = 1.0;
  const ServoAmplifierBlock with_ff(p);
  p.velocity_feedforward = 0.0;
  const ServoAmplifierBlock without(p);
  Io a = make_io(with_ff), b = make_io(without);
  with_ff.calc_outputs(0.15, a.x, a.u, a.y);  // cruising at 0.1 m/s
  without.calc_outputs(0.15, b.x, b.u, b.y);
  const int e = with_ff.output_index("velocity_error");
  EXPECT_NEAR(a.y[e] - b.y[e], 0.0496 * 0.1 * radians_per_metre, 1e-12);
}

TEST(ServoAmplifierBlockTest, SampledOutputIsHeldBetweenUpdates) {
  ServoAmplifierParams p;
  p.sample_time = 1e-3;
  ServoAmplifierBlock dut(p);
  Io io = make_io(dut);
  io.x = {0.5, 0.0};
  dut.discrete_update(0.0, io.x, io.u);
  dut.calc_outputs(0.0, io.x, io.u, io.y);
  const int v = dut.output_index("armature_voltage");
  const double held = io.y[v];
  EXPECT_NEAR(held, 10 * 0.0496 * 40 * 1e-4 * radians_per_metre + 0.5, 1e-12);
  // Inputs and states move; output and derivatives keep using the samples of t = 0.
  std::vector<double> dx_before(2), dx_after(2);
  dut.derivatives(0.0005, io.x, io.u, dx_before);
  io.u[dut.input_index("spindle_angle")] = 0.05;
  io.u[dut.input_index("tacho_voltage")] = 1.0;
  dut.calc_outputs(0.0005, io.x, io.u, io.y);
  EXPECT_EQ(io.y[v], held);
  dut.derivatives(0.0005, io.x, io.u, dx_after);
  EXPECT_EQ(dx_after, dx_before);
  // The next sample takes the new inputs.
  const auto saved = dut.save_discrete_state();
  dut.discrete_update(1e-3, io.x, io.u);
  dut.calc_outputs(1e-3, io.x, io.u, io.y);
  EXPECT_NE(io.y[v], held);
  // Restoring the checkpoint brings the held output back; reset returns to zeros.
  dut.restore_discrete_state(saved);
  dut.calc_outputs(1e-3, io.x, io.u, io.y);
  EXPECT_EQ(io.y[v], held);
  dut.reset_discrete_state();
  dut.calc_outputs(1e-3, io.x, io.u, io.y);
  EXPECT_EQ(io.y[v], 0.0);
}

TEST(ServoAmplifierBlockTest, RejectsNonPhysicalParameters) {
  ServoAmplifierParams p;
  p.voltage_limit = 0;
  EXPECT_THROW(ServoAmplifierBlock{p}, std::invalid_argument);
  p = {};
  p.sample_time = -1e-3;
  EXPECT_THROW(ServoAmplifierBlock{p}, std::invalid_argument);
  p = {};
  p.setpoint = {SetpointKind::trapezoid, 0, 0.02, 0.1, 0.0};
  EXPECT_THROW(ServoAmplifierBlock{p}, std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::nc
