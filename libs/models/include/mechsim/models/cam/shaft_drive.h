// What turns the cam shaft (spec cam.md §4, dynamic drive): an ideal speed source, or a
// torque source acting on the shaft's inertia (shaft + flywheel) — a constant torque or a
// motor's torque–speed line T = T_stall (1 − ω/ω0), as for a DC or induction motor near
// its operating point.
#pragma once

namespace mechsim::models::cam {

enum class DriveType {
  constant_speed,   // ω fixed: the drive delivers whatever torque the load demands
  constant_torque,  // T = torque
  motor_line,       // T = stall_torque (1 − ω/no_load_speed)
};

// Lower-case name as written in scenes ("constant_speed", ...).
const char* drive_type_name(DriveType type);

struct ShaftDrive {
  DriveType type = DriveType::constant_speed;
  double torque_nm = 0.0;           // constant_torque
  double stall_torque_nm = 0.0;     // motor_line, > 0
  double no_load_speed_rad_s = 0.0; // motor_line, > 0

  bool is_torque_source() const { return type != DriveType::constant_speed; }
  // Torque the drive puts on the shaft at speed ω (torque sources only; a speed source has
  // no characteristic: its torque is the load's).
  double torque_at(double speed_rad_s) const;
};

// Throws std::invalid_argument for a non-finite torque or a motor line without a positive
// stall torque and no-load speed.
void validate(const ShaftDrive& drive);

// Speed at which a motor line delivers the mean load torque: ω0 (1 − M_mean/T_stall).
// With a periodic load this is the cycle-mean speed up to terms of order K² (K the speed
// fluctuation coefficient), since the drive's work ∮T dθ is linear in ∮ω dθ.
double motor_line_steady_speed(const ShaftDrive& drive, double mean_load_torque_nm);

// Polar moment of inertia of a solid disc: I = π ρ t R⁴ / 2 (the inverse of the spec's
// R = (2I/(π t ρ))^(1/4)).
double disc_inertia(double radius_m, double thickness_m, double density_kg_m3);

}  // namespace mechsim::models::cam
