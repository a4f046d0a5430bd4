// Time-domain block of the motor–tachometer combination (spec nc_slide.md §1):
//
//   L_a di_a/dt = U_a − R_a i_a − c ω1
//   I1 dω1/dt   = c i_a − b1 ω1 − b3 (ω1 − ω2) − k θ − T_load
//   I2 dω2/dt   = k θ + b3 (ω1 − ω2) − b2 ω2
//   dθ/dt       = ω1 − ω2,   dφ1/dt = ω1       (φ1 is added for the coupling: 5 states)
//
// T_load is the coupling torque on the rotor: the input load_torque, or, with
// CouplingInput::compliant, C_kopp (φ1 − φ_a) + d_k (ω1 − ω_a) from the spindle's angle and
// speed (inputs spindle_angle, spindle_speed; the evaluated torque is output coupling_torque).
//
// Ports                          unit    feedthrough
//   in  armature_voltage         V       required
//   in  load_torque              N m     default 0           (torque coupling only)
//   in  spindle_angle            rad     default 0           (compliant coupling only)
//   in  spindle_speed            rad/s   default 0           (compliant coupling only)
//   out tacho_voltage            V       —   U_T = α ω2
//   out motor_angle              rad     —   φ1
//   out motor_speed              rad/s   —   ω1
//   out armature_current         A       —   i_a
//   out coupling_torque          N m     spindle_angle, spindle_speed (compliant only)
// States: armature_current [A], motor_speed [rad/s], tacho_speed [rad/s], shaft_twist [rad],
// motor_angle [rad]; all zero initially (at rest).
#pragma once

#include "mechsim/models/block.h"
#include "mechsim/models/nc/coupling.h"
#include "mechsim/models/nc/motor_tacho.h"

namespace mechsim::models::nc {

struct MotorTachoBlockOptions {
  MotorTachoParams motor;
  CouplingInput coupling_input = CouplingInput::torque;
  CouplingParams coupling;  // used with CouplingInput::compliant
};

class MotorTachoBlock final : public Block {
 public:
  explicit MotorTachoBlock(MotorTachoBlockOptions options = {});

  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const MotorTachoBlockOptions& options() const { return options_; }

 private:
  double load_torque(std::span<const double> x, std::span<const double> u) const;

  MotorTachoBlockOptions options_;
  struct Inputs {
    int armature_voltage = -1, load_torque = -1, spindle_angle = -1, spindle_speed = -1;
  } in_;
  struct Outputs {
    int tacho_voltage = -1, motor_angle = -1, motor_speed = -1, armature_current = -1, coupling_torque = -1;
  } out_;
  struct States {
    int armature_current, motor_speed, tacho_speed, shaft_twist, motor_angle;
  } st_;
};

}  // namespace mechsim::models::nc
