#include "mechsim/models/nc/motor_tacho_block.h"

#include <stdexcept>

namespace mechsim::models::nc {

MotorTachoBlock::MotorTachoBlock(MotorTachoBlockOptions options)
    : Block("motor_tacho"), options_(options) {
  const auto& m = options_.motor;
  if (!(m.armature_resistance > 0 && m.armature_inductance > 0 && m.torque_constant > 0 &&
        m.motor_inertia > 0 && m.tacho_inertia > 0 && m.shaft_stiffness > 0))
    throw std::invalid_argument("motor_tacho: R_a, L_a, c, I1, I2 and k must be > 0");

  in_.armature_voltage = declare_required_input("armature_voltage", "V");
  std::vector<int> coupling_feedthrough;
  if (options_.coupling_input == CouplingInput::torque) {
    in_.load_torque = declare_input("load_torque", "N m", 0.0);
  } else {
    in_.spindle_angle = declare_input("spindle_angle", "rad", 0.0);
    in_.spindle_speed = declare_input("spindle_speed", "rad/s", 0.0);
    coupling_feedthrough = {in_.spindle_angle, in_.spindle_speed};
  }
  out_.tacho_voltage = declare_output("tacho_voltage", "V");
  out_.motor_angle = declare_output("motor_angle", "rad");
  out_.motor_speed = declare_output("motor_speed", "rad/s");
  out_.armature_current = declare_output("armature_current", "A");
  if (options_.coupling_input == CouplingInput::compliant)
    out_.coupling_torque = declare_output("coupling_torque", "N m", coupling_feedthrough);

  st_.armature_current = declare_state("armature_current", "A");
  st_.motor_speed = declare_state("motor_speed", "rad/s");
  st_.tacho_speed = declare_state("tacho_speed", "rad/s");
  st_.shaft_twist = declare_state("shaft_twist", "rad");
  st_.motor_angle = declare_state("motor_angle", "rad");
}

double MotorTachoBlock::load_torque(std::span<const double> x, std::span<const double> u) const {
  if (options_.coupling_input == CouplingInput::torque) return u[in_.load_torque];
  return coupling_torque(options_.coupling, x[st_.motor_angle], x[st_.motor_speed], u[in_.spindle_angle],
                         u[in_.spindle_speed]);
}

void MotorTachoBlock::derivatives(double, std::span<const double> x, std::span<const double> u,
                                  std::span<double> dxdt) const {
  const auto& m = options_.motor;
  const double i_a = x[st_.armature_current], w1 = x[st_.motor_speed], w2 = x[st_.tacho_speed];
  const double twist = x[st_.shaft_twist];
  const double shaft_torque = m.shaft_stiffness * twist + m.shaft_damping * (w1 - w2);
  dxdt[st_.armature_current] =
      (u[in_.armature_voltage] - m.armature_resistance * i_a - m.torque_constant * w1) / m.armature_inductance;
  dxdt[st_.motor_speed] =
      (m.torque_constant * i_a - m.motor_damping * w1 - shaft_torque - load_torque(x, u)) / m.motor_inertia;
  dxdt[st_.tacho_speed] = (shaft_torque - m.tacho_damping * w2) / m.tacho_inertia;
  dxdt[st_.shaft_twist] = w1 - w2;
  dxdt[st_.motor_angle] = w1;
}

void MotorTachoBlock::calc_outputs(double, std::span<const double> x, std::span<const double> u,
                                   std::span<double> y) const {
  y[out_.tacho_voltage] = options_.motor.tacho_constant * x[st_.tacho_speed];
  y[out_.motor_angle] = x[st_.motor_angle];
  y[out_.motor_speed] = x[st_.motor_speed];
  y[out_.armature_current] = x[st_.armature_current];
  if (out_.coupling_torque >= 0) y[out_.coupling_torque] = load_torque(x, u);
}

}  // namespace mechsim::models::nc
