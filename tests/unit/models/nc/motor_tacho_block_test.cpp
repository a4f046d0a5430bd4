// MotorTachoBlock (spec nc_slide.md §1, time domain).
#include "mechsim/models/nc/motor_tacho_block.h"

#include <gtest/gtest.h>

#include <random>

#include "fixed_step_rk4.h"

namespace mechsim::models::nc {
namespace {

TEST(MotorTachoBlockTest, Topology) {
  const MotorTachoBlock dut;
  ASSERT_EQ(dut.num_inputs(), 2);
  EXPECT_TRUE(dut.inputs()[dut.input_index("armature_voltage")].required);
  EXPECT_FALSE(dut.inputs()[dut.input_index("load_torque")].required);
  EXPECT_EQ(dut.inputs()[dut.input_index("load_torque")].default_value, 0.0);
  for (const char* name : {"tacho_voltage", "motor_angle", "motor_speed", "armature_current"}) {
    const int i = dut.output_index(name);
    ASSERT_GE(i, 0) << name;
    EXPECT_TRUE(dut.outputs()[i].feedthrough.empty()) << name;  // all from states
  }
  EXPECT_EQ(dut.output_index("coupling_torque"), -1);
  EXPECT_EQ(dut.num_states(), 5);
}

TEST(MotorTachoBlockTest, DerivativesEqualTheStateSpaceModel) {
  const MotorTachoParams params;
  MotorTachoBlockOptions options;
  options.motor = params;
  const MotorTachoBlock dut(options);
  const auto ss = state_space(params);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<double> x(5), u{50 * uniform(rng), 5 * uniform(rng)}, dx(5), y(4);
    x = {100 * uniform(rng), 300 * uniform(rng), 300 * uniform(rng), 1e-2 * uniform(rng), 10 * uniform(rng)};
    dut.derivatives(0, x, u, dx);
    const Eigen::Vector4d xs(x[0], x[1], x[2], x[3]);  // block order i_a, ω1, ω2, θ
    const Eigen::Vector4d expected = ss.a * xs + ss.b * Eigen::Vector2d(u[0], u[1]);
    // Same arithmetic in another order: relative round-off of the largest term.
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(dx[i], expected(i), 1e-12 * (ss.a.row(i).cwiseAbs() * xs.cwiseAbs()).sum() + 1e-12 * std::abs(expected(i)) + 1e-9);
    EXPECT_EQ(dx[4], x[1]);  // dφ1/dt = ω1
    dut.calc_outputs(0, x, u, y);
    EXPECT_DOUBLE_EQ(y[dut.output_index("tacho_voltage")], params.tacho_constant * x[2]);
  }
}

TEST(MotorTachoBlockTest, SettlesAtTheDcGainWithTheLoadTorqueUnconnected) {
  MotorTachoBlock dut;
  std::vector<double> u = dut.default_inputs();
  u[dut.input_index("armature_voltage")] = 10.0;
  // The slowest decay is the shaft pair's, −37.6 s⁻¹: after 0.6 s its transient is
  // e^(−22.6) ≈ 1.5e-10 of the step.
  const auto tr = testing::integrate_rk4(dut, 0.6, 1e-5, u, 1000);
  EXPECT_NEAR(tr.outputs.back()[dut.output_index("tacho_voltage")], 0.248 * 10.0, 1e-6);
}

TEST(MotorTachoBlockTest, CompliantCouplingEvaluatesTheSpringDamper) {
  const CouplingParams coupling{23e3, 0.15};
  const MotorTachoBlock compliant({MotorTachoParams{}, CouplingInput::compliant, coupling});
  const MotorTachoBlock torque_input;
  ASSERT_EQ(compliant.input_index("load_torque"), -1);
  const int out = compliant.output_index("coupling_torque");
  ASSERT_GE(out, 0);
  const auto& ft = compliant.outputs()[out].feedthrough;
  EXPECT_EQ(ft.size(), 2u);  // spindle_angle and spindle_speed reach it directly

  const std::vector<double> x{3.0, 50.0, 49.0, 1e-3, 0.20};
  std::vector<double> u(3);
  u[compliant.input_index("armature_voltage")] = 12.0;
  u[compliant.input_index("spindle_angle")] = 0.199;
  u[compliant.input_index("spindle_speed")] = 49.5;
  const double expected = 23e3 * (0.20 - 0.199) + 0.15 * (50.0 - 49.5);
  std::vector<double> y(compliant.num_outputs()), dx1(5), dx2(5);
  compliant.calc_outputs(0, x, u, y);
  EXPECT_NEAR(y[out], expected, 1e-12 * 23);
  // Same dynamics as the torque variant fed with that torque (bit-for-bit up to round-off).
  compliant.derivatives(0, x, u, dx1);
  torque_input.derivatives(0, x, std::vector<double>{12.0, expected}, dx2);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(dx1[i], dx2[i], 1e-9 * (1 + std::abs(dx2[i])));
}

TEST(MotorTachoBlockTest, RejectsNonPhysicalParameters) {
  MotorTachoParams p;
  p.tacho_inertia = 0;
  MotorTachoBlockOptions options;
  options.motor = p;
  EXPECT_THROW(MotorTachoBlock{options}, std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::nc
