// SlideBlock variants (spec nc_slide.md §2–§3, time domain).
#include "mechsim/models/nc/slide_block.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fixed_step_rk4.h"
#include "mechsim/models/nc/slide_torsion.h"

namespace mechsim::models::nc {
namespace {

constexpr double two_pi = 2 * std::numbers::pi;

// Linearisation dx/dt = A x (+ B u) by central differences; the block is linear without
// Coulomb friction, so the differences are exact up to round-off.
Eigen::MatrixXd linearise(const Block& block, const std::vector<double>& u) {
  const int n = block.num_states();
  Eigen::MatrixXd a(n, n);
  std::vector<double> x(n, 0.0), plus(n), minus(n);
  for (int j = 0; j < n; ++j) {
    x[j] = 1e-3;
    block.derivatives(0, x, u, plus);
    x[j] = -1e-3;
    block.derivatives(0, x, u, minus);
    x[j] = 0;
    for (int i = 0; i < n; ++i) a(i, j) = (plus[i] - minus[i]) / 2e-3;
  }
  return a;
}

// Natural frequencies [Hz] of a block's linearisation, ascending, without the rigid modes
// (their double zero eigenvalue comes out as round-off, far below 1 Hz).
std::vector<double> natural_frequencies_hz(const Block& block, const std::vector<double>& u) {
  Eigen::EigenSolver<Eigen::MatrixXd> solver(linearise(block, u), false);
  std::vector<double> f;
  for (int i = 0; i < solver.eigenvalues().size(); ++i)
    if (solver.eigenvalues()(i).imag() >= 0 && std::abs(solver.eigenvalues()(i)) / two_pi > 1.0) f.push_back(std::abs(solver.eigenvalues()(i)) / two_pi);
  std::sort(f.begin(), f.end());
  return f;
}

SlideBlockOptions undamped(SlideVariant variant) {
  SlideBlockOptions o;
  o.variant = variant;
  o.spindle_damping = 0;
  o.guide_viscous_friction = 0;
  return o;
}

TEST(SlideBlockTest, Topology) {
  const SlideBlock dut;
  EXPECT_EQ(dut.num_states(), 4);  // two-mass by default
  ASSERT_EQ(dut.num_inputs(), 1);
  EXPECT_EQ(dut.inputs()[0].name, "drive_torque");
  EXPECT_EQ(dut.inputs()[0].default_value, 0.0);
  for (const char* name : {"spindle_angle", "spindle_speed", "slide_position", "slide_speed"})
    EXPECT_TRUE(dut.outputs()[dut.output_index(name)].feedthrough.empty()) << name;
  EXPECT_EQ(dut.outputs()[dut.output_index("coupling_torque")].feedthrough, std::vector<int>{0});

  SlideBlockOptions compliant;
  compliant.coupling_input = CouplingInput::compliant;
  const SlideBlock c(compliant);
  EXPECT_EQ(c.input_index("drive_torque"), -1);
  EXPECT_GE(c.input_index("motor_angle"), 0);
  EXPECT_GE(c.input_index("motor_speed"), 0);

  SlideBlockOptions modal;
  modal.variant = SlideVariant::modal;
  modal.modal_shapes = 5;
  EXPECT_EQ(SlideBlock(modal).num_states(), 10);
  SlideBlockOptions rigid;
  rigid.variant = SlideVariant::rigid;
  EXPECT_EQ(SlideBlock(rigid).num_states(), 2);
}

TEST(SlideBlockTest, RigidSlideUnderConstantTorqueFollowsTheClosedForm) {
  SlideBlockOptions o;
  o.variant = SlideVariant::rigid;
  SlideBlock dut(o);
  const SlideDriveData& d = o.drive;
  const double inertia = d.coupling_inertia + d.spindle_inertia() + d.slide_inertia();
  const double r = d.metres_per_radian();
  const double viscous = o.guide_viscous_friction * r * r;  // c_v reduced to the spindle
  const double torque = 0.5, t_end = 0.5;
  const auto tr = testing::integrate_rk4(dut, t_end, 1e-4, {torque});
  // I ω' = T − c ω  =>  ω(t) = T/c (1 − e^(−c t/I)). RK4 at h = 1e-4 on a 1.4 s time
  // constant: local error ~ (h/τ)^5, far below 1e-9 relative.
  const double omega = torque / viscous * (1 - std::exp(-viscous * t_end / inertia));
  EXPECT_NEAR(tr.outputs.back()[dut.output_index("spindle_speed")], omega, 1e-9 * omega);
  EXPECT_NEAR(tr.outputs.back()[dut.output_index("slide_speed")], r * omega, 1e-9 * r * omega);
}

TEST(SlideBlockTest, TwoMassFreeFrequencyIsTheSpindleMode) {
  const SlideBlockOptions o = undamped(SlideVariant::two_mass);
  const SlideBlock dut(o);
  const SlideDriveData& d = o.drive;
  const double i_a = d.coupling_inertia + d.spindle_inertia() / 2, i_b = d.slide_inertia() + d.spindle_inertia() / 2;
  const double expected = std::sqrt(d.spindle_stiffness() * (i_a + i_b) / (i_a * i_b)) / two_pi;
  const auto f = natural_frequencies_hz(dut, {0.0});
  ASSERT_EQ(f.size(), 1u);
  // Finite differences of a linear map: exact up to round-off (1e-6 relative is generous).
  EXPECT_NEAR(f.back(), expected, 1e-6 * expected);
}

TEST(SlideBlockTest, CompliantTwoMassWithTheMotorHeldIsModelTwo) {
  // Motor angle and speed held at 0: frame —C_kopp— I_a —C_sp— I_b, the report's model 2.
  SlideBlockOptions o = undamped(SlideVariant::two_mass);
  o.drive = SlideDriveData::report_cnc200();
  o.coupling_input = CouplingInput::compliant;
  o.coupling.damping = 0;
  const SlideBlock dut(o);
  const auto f = natural_frequencies_hz(dut, {0.0, 0.0});
  const auto expected = grounded_chain_frequencies_hz(o.drive);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[0], expected.first_hz, 1e-6 * expected.first_hz);
  EXPECT_NEAR(f[1], expected.second_hz, 1e-6 * expected.second_hz);
}

TEST(SlideBlockTest, ModalVariantConvergesToTheFeChainOfTheSpindle) {
  SlideBlockOptions o = undamped(SlideVariant::modal);
  o.nut_position = 0.6;
  const SlideDriveData& d = o.drive;
  const UniformShaft spindle{d.spindle_length, d.shear_modulus * d.polar_moment(), d.density * d.polar_moment()};
  const double fe = fe_chain_frequencies_hz(spindle, {{0.0, d.coupling_inertia}, {0.6, d.slide_inertia()}}, 2000)(1);
  double previous = INFINITY;
  for (int n : {2, 4, 8, 16, 32}) {
    o.modal_shapes = n;
    const double f = natural_frequencies_hz(SlideBlock(o), {0.0}).front();
    EXPECT_LE(f, previous * (1 + 1e-9)) << n;  // Ritz: nested upper bounds
    EXPECT_GT(f, fe * (1 - 1e-6)) << n;        // FE at 2000 elements is converged to < 1e-6
    previous = f;
  }
  // About 1/N convergence: at N = 32 within 0.1 %.
  EXPECT_NEAR(previous, fe, 1e-3 * fe);
}

TEST(SlideBlockTest, ModalWithOneShapeIsTheRigidSlide) {
  SlideBlockOptions modal;
  modal.variant = SlideVariant::modal;
  modal.modal_shapes = 1;
  SlideBlockOptions rigid;
  rigid.variant = SlideVariant::rigid;
  SlideBlock m(modal), r(rigid);
  const auto tm = testing::integrate_rk4(m, 0.1, 1e-4, {0.3});
  const auto tr = testing::integrate_rk4(r, 0.1, 1e-4, {0.3});
  // Same inertia (∫ρJ dx + I_kopp + I_slide = I_sp + I_kopp + I_slide), same friction.
  const int i = m.output_index("slide_position");
  EXPECT_NEAR(tm.outputs.back()[i], tr.outputs.back()[i], 1e-12 * std::abs(tr.outputs.back()[i]));
}

TEST(SlideBlockTest, CoulombFrictionIsSmoothedWithTanh) {
  SlideBlockOptions o;
  o.guide_coulomb_friction = 300;
  o.coulomb_velocity_scale = 1e-4;
  const SlideBlock dut(o);
  const double r = o.drive.metres_per_radian();
  // Far above v_s: tanh = 1 to 1e-15; exactly odd; zero at rest.
  EXPECT_NEAR(dut.guide_friction_torque(0.01), r * (2000 * 0.01 + 300), 1e-12);
  EXPECT_DOUBLE_EQ(dut.guide_friction_torque(-0.01), -dut.guide_friction_torque(0.01));
  EXPECT_EQ(dut.guide_friction_torque(0.0), 0.0);
  // At v = v_s: tanh(1) of the Coulomb force.
  EXPECT_NEAR(dut.guide_friction_torque(1e-4), r * (2000 * 1e-4 + 300 * std::tanh(1.0)), 1e-12);
}

TEST(SlideBlockTest, CouplingTorqueOutputFollowsTheCouplingInput) {
  SlideBlockOptions o;
  o.coupling_input = CouplingInput::compliant;
  const SlideBlock dut(o);
  std::vector<double> x{0.1, 0.099, 5.0, 4.0}, y(dut.num_outputs());
  std::vector<double> u(2);
  u[dut.input_index("motor_angle")] = 0.1002;
  u[dut.input_index("motor_speed")] = 5.5;
  dut.calc_outputs(0, x, u, y);
  EXPECT_NEAR(y[dut.output_index("coupling_torque")], 23e3 * 0.0002 + 0.15 * 0.5, 1e-10);
  EXPECT_NEAR(y[dut.output_index("slide_position")], 0.099 * 0.005 / two_pi, 1e-15);
}

TEST(SlideBlockTest, RejectsBadModalSettings) {
  SlideBlockOptions o;
  o.variant = SlideVariant::modal;
  o.modal_shapes = 0;
  EXPECT_THROW(SlideBlock{o}, std::invalid_argument);
  o.modal_shapes = 3;
  o.nut_position = 2.0;
  EXPECT_THROW(SlideBlock{o}, std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::nc
