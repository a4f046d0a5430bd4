// The motor–spindle coupling C_kopp, d_k (spec nc_slide.md §2–§3). It sits at the cut
// between the motor rotor (tachometer node) and the spindle's drive end and belongs to the
// connection (DESIGN.md, "Coupling across stiff cuts"): the composer adds it once to the
// reference; in a co-simulation both sides may evaluate it from their own state and the
// partner's angle and speed (CouplingInput::compliant).
#pragma once

namespace mechsim::models::nc {

struct CouplingParams {
  double stiffness = 23e3;  // C_kopp [N m/rad]
  double damping = 0.15;    // d_k [N m s/rad]
};

// How a block at the cut receives the coupling: as a torque input, or as the partner's
// angle and speed with the spring-damper evaluated inside the block.
enum class CouplingInput { torque, compliant };

// Torque transmitted from the motor to the spindle [N m]: positive drives the spindle
// forwards and loads the motor (it is the motor block's load_torque).
inline double coupling_torque(const CouplingParams& coupling, double motor_angle, double motor_speed,
                              double spindle_angle, double spindle_speed) {
  return coupling.stiffness * (motor_angle - spindle_angle) + coupling.damping * (motor_speed - spindle_speed);
}

}  // namespace mechsim::models::nc
