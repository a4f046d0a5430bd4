#include "mechsim/models/cam/shaft_drive.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mechsim::models::cam {

const char* drive_type_name(DriveType type) {
  switch (type) {
    case DriveType::constant_speed: return "constant_speed";
    case DriveType::constant_torque: return "constant_torque";
    case DriveType::motor_line: return "motor_line";
  }
  return "?";
}

double ShaftDrive::torque_at(double speed_rad_s) const {
  switch (type) {
    case DriveType::constant_torque: return torque_nm;
    case DriveType::motor_line: return stall_torque_nm * (1.0 - speed_rad_s / no_load_speed_rad_s);
    case DriveType::constant_speed: break;
  }
  throw std::logic_error("ShaftDrive::torque_at: a constant-speed drive has no torque characteristic");
}

void validate(const ShaftDrive& drive) {
  switch (drive.type) {
    case DriveType::constant_speed: return;
    case DriveType::constant_torque:
      if (!std::isfinite(drive.torque_nm)) throw std::invalid_argument("shaft drive: the torque must be finite");
      return;
    case DriveType::motor_line:
      if (!(drive.stall_torque_nm > 0.0 && std::isfinite(drive.stall_torque_nm)))
        throw std::invalid_argument("shaft drive: the motor line needs a stall torque > 0");
      if (!(drive.no_load_speed_rad_s > 0.0 && std::isfinite(drive.no_load_speed_rad_s)))
        throw std::invalid_argument("shaft drive: the motor line needs a no-load speed > 0");
      return;
  }
}

double motor_line_steady_speed(const ShaftDrive& drive, double mean_load_torque_nm) {
  if (drive.type != DriveType::motor_line) throw std::invalid_argument("motor_line_steady_speed: not a motor line");
  return drive.no_load_speed_rad_s * (1.0 - mean_load_torque_nm / drive.stall_torque_nm);
}

double disc_inertia(double radius_m, double thickness_m, double density_kg_m3) {
  if (!(radius_m > 0.0 && thickness_m > 0.0 && density_kg_m3 > 0.0))
    throw std::invalid_argument("disc_inertia: radius, thickness and density must be > 0");
  return std::numbers::pi * density_kg_m3 * thickness_m * std::pow(radius_m, 4) / 2.0;
}

}  // namespace mechsim::models::cam
