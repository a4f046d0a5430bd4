// The cam shaft's drives (constant speed, constant torque, motor line) and the dynamic
// shaft block: ports, states and the equation (I + m S'²) ω̇ = T_drive(ω) − M_rest.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/cam/design.h"
#include "mechsim/models/cam/press_cam.h"
#include "mechsim/models/cam/shaft_drive.h"

namespace mechsim::models::cam {
namespace {

constexpr double pi = std::numbers::pi;

ShaftDrive motor_line(double stall, double no_load) {
  ShaftDrive d;
  d.type = DriveType::motor_line;
  d.stall_torque_nm = stall;
  d.no_load_speed_rad_s = no_load;
  return d;
}

CamShaftParams dynamic_press_cam(ShaftDrive drive, double inertia, double initial_speed) {
  const PressCam c;
  CamShaftParams p{c.law(), c.pitch_radius_m, -0.0035, pi, 0.3};
  p.drive = drive;
  p.inertia_kgm2 = inertia;
  p.initial_speed = initial_speed;
  return p;
}

TEST(ShaftDrive, Characteristics) {
  ShaftDrive constant;
  constant.type = DriveType::constant_torque;
  constant.torque_nm = 0.46;
  EXPECT_EQ(constant.torque_at(0.0), 0.46);
  EXPECT_EQ(constant.torque_at(10.0), 0.46);
  const ShaftDrive line = motor_line(20.0, 4.0);
  // T = T_stall (1 − ω/ω0): the stall torque at rest, nothing at no-load speed, linear between.
  EXPECT_EQ(line.torque_at(0.0), 20.0);
  EXPECT_EQ(line.torque_at(4.0), 0.0);
  EXPECT_DOUBLE_EQ(line.torque_at(1.0), 15.0);
  EXPECT_DOUBLE_EQ(line.torque_at(5.0), -5.0);  // above no-load speed it brakes
  // Where the line delivers the mean load torque: 4 (1 − 5/20) = 3 rad/s.
  EXPECT_DOUBLE_EQ(motor_line_steady_speed(line, 5.0), 3.0);
  EXPECT_THROW(ShaftDrive{}.torque_at(1.0), std::logic_error);  // a speed source has no characteristic
  EXPECT_THROW(validate(motor_line(0.0, 4.0)), std::invalid_argument);
  EXPECT_THROW(validate(motor_line(20.0, -1.0)), std::invalid_argument);
}

TEST(ShaftDrive, DiscInertiaInvertsTheDesignRadius) {
  // The design gives R = (2I/(π t ρ))^(1/4); a disc of that radius has the inertia I again.
  const PressCam c;
  const TorqueAnalysis torque = drive_torque_analysis(c.law(), c.follower, c.speed_rad_s);
  const FlywheelDesign fw = flywheel_design(torque, 0.1, c.speed_rad_s, 7800.0, 0.05);
  EXPECT_NEAR(disc_inertia(fw.disc_radius_m, 0.05, 7800.0), fw.inertia_kgm2, 1e-12 * fw.inertia_kgm2);
  EXPECT_THROW(disc_inertia(0.0, 0.05, 7800.0), std::invalid_argument);
}

TEST(CamShaftBlock, TorqueDriveHasAngleAndSpeedStates) {
  const CamShaftBlock b(dynamic_press_cam(motor_line(20.0, 4.0), 2.0, 1.5));
  EXPECT_TRUE(b.has_dynamic_drive());
  EXPECT_EQ(b.state_names(), (std::vector<std::string>{"angle", "speed"}));
  // Only the acceleration feeds through (from both inputs); everything else is state.
  const std::vector<int> both{0, 1}, none;
  for (const auto& o : b.outputs()) EXPECT_EQ(o.feedthrough, o.name == "acceleration" ? both : none) << o.name;
  std::vector<double> x(2);
  b.initial_state(0.0, x);
  EXPECT_EQ(x[0], 0.3);
  EXPECT_EQ(x[1], 1.5);
}

TEST(CamShaftBlock, TorqueDriveEquationCarriesTheReflectedInertia) {
  const CamShaftBlock b(dynamic_press_cam(motor_line(20.0, 4.0), 2.0, 1.5));
  const std::vector<double> x{2.0, 1.0}, u{3.0, 0.5};  // M_rest = 3 N m, J_r = 0.5 kg m²
  std::vector<double> dxdt(2), y(b.num_outputs());
  b.derivatives(0.0, x, u, dxdt);
  EXPECT_EQ(dxdt[0], 1.0);
  // (I + J_r) ω̇ = T(ω) − M_rest: (2 + 0.5) ω̇ = 15 − 3.
  EXPECT_DOUBLE_EQ(dxdt[1], 12.0 / 2.5);
  b.calc_outputs(7.0, x, u, y);  // the time does not matter: the angle is a state
  const LawPoint p = PressCam{}.law().evaluate(2.0);
  EXPECT_EQ(y[b.output_index("angle")], 2.0);
  EXPECT_EQ(y[b.output_index("speed")], 1.0);
  EXPECT_EQ(y[b.output_index("lift")], p.s);
  EXPECT_EQ(y[b.output_index("acceleration")], dxdt[1]);
  EXPECT_DOUBLE_EQ(y[b.output_index("shaft_torque")], 15.0);  // the motor's torque, not the load's
  EXPECT_DOUBLE_EQ(y[b.output_index("drive_power")], 15.0);
}

TEST(CamShaftBlock, TorqueDriveRefusesAShaftWithoutInertia) {
  ShaftDrive d;
  d.type = DriveType::constant_torque;
  d.torque_nm = 1.0;
  EXPECT_THROW(CamShaftBlock(dynamic_press_cam(d, 0.0, 1.0)), std::invalid_argument);
  EXPECT_NO_THROW(CamShaftBlock(dynamic_press_cam(d, 1e-3, 1.0)));
}

}  // namespace
}  // namespace mechsim::models::cam
