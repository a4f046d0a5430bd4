#include "mechsim/models/cam/cam_shaft_block.h"

#include <cmath>
#include <stdexcept>

#include "mechsim/models/cam/geometry.h"

namespace mechsim::models::cam {

namespace {
// Port indices, fixed by the declaration order in the constructor.
enum Input { in_load_torque, in_reflected_inertia };
enum Output { out_angle, out_speed, out_lift, out_lift_d1, out_lift_d2, out_pressure_angle,
              out_shaft_torque, out_drive_power, out_acceleration };
enum State { x_angle, x_speed };
}  // namespace

CamShaftBlock::CamShaftBlock(CamShaftParams params) : Block("cam_shaft"), params_(std::move(params)) {
  if (!(params_.pitch_radius > 0.0)) throw std::invalid_argument("cam_shaft: pitch radius must be > 0");
  if (!(std::abs(params_.eccentricity) < params_.pitch_radius))
    throw std::invalid_argument("cam_shaft: |eccentricity| must be smaller than the pitch radius");
  if (!std::isfinite(params_.speed) || !std::isfinite(params_.initial_angle))
    throw std::invalid_argument("cam_shaft: speed and initial angle must be finite");
  validate(params_.drive);
  const bool dynamic = params_.drive.is_torque_source();
  if (dynamic) {
    // Dwells reflect no follower inertia: the shaft's own inertia must carry ω̇ there.
    if (!(params_.inertia_kgm2 > 0.0 && std::isfinite(params_.inertia_kgm2)))
      throw std::invalid_argument("cam_shaft: a torque drive needs a shaft inertia > 0");
    if (params_.initial_speed && !std::isfinite(*params_.initial_speed))
      throw std::invalid_argument("cam_shaft: the initial speed must be finite");
  }
  const int load = declare_input("load_torque", "N*m", 0.0);
  const int reflected = declare_input("reflected_inertia", "kg*m^2", 0.0);
  declare_output("angle", "rad");
  declare_output("speed", "rad/s");
  declare_output("lift", "m");
  declare_output("lift_d1", "m/rad");
  declare_output("lift_d2", "m/rad^2");
  declare_output("pressure_angle", "rad");
  declare_output("shaft_torque", "N*m", dynamic ? std::vector<int>{} : std::vector<int>{load});
  declare_output("drive_power", "W", dynamic ? std::vector<int>{} : std::vector<int>{load});
  declare_output("acceleration", "rad/s^2", dynamic ? std::vector<int>{load, reflected} : std::vector<int>{});
  if (dynamic) {
    declare_state("angle", "rad");
    declare_state("speed", "rad/s");
  }
}

double CamShaftBlock::angular_acceleration(double speed, double load_torque_rest, double reflected_inertia) const {
  if (!has_dynamic_drive()) return 0.0;
  return (params_.drive.torque_at(speed) - load_torque_rest) / (params_.inertia_kgm2 + reflected_inertia);
}

void CamShaftBlock::initial_state(double, std::span<double> x) const {
  if (!has_dynamic_drive()) return;
  x[x_angle] = params_.initial_angle;
  x[x_speed] = params_.initial_speed.value_or(params_.speed);
}

void CamShaftBlock::derivatives(double, std::span<const double> x, std::span<const double> u,
                                std::span<double> dxdt) const {
  if (!has_dynamic_drive()) return;
  dxdt[x_angle] = x[x_speed];
  dxdt[x_speed] = angular_acceleration(x[x_speed], u[in_load_torque], u[in_reflected_inertia]);
}

void CamShaftBlock::calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                                 std::span<double> y) const {
  double theta, omega, omega_dot, torque;
  if (has_dynamic_drive()) {
    theta = x[x_angle];
    omega = x[x_speed];
    omega_dot = angular_acceleration(omega, u[in_load_torque], u[in_reflected_inertia]);
    torque = params_.drive.torque_at(omega);
  } else {
    // Constant speed: the angle is a function of time, not an integrated state, so every
    // process (and the reference) computes bit-identical angles at the same t. Integrating
    // it would let rounding decide on which side of a load boundary a sample falls.
    theta = params_.initial_angle + params_.speed * t;
    omega = params_.speed;
    omega_dot = 0.0;
    torque = u[in_load_torque];  // ω̇ = 0: the reflected inertia takes no torque
  }
  const LawPoint p = params_.law.evaluate(theta);
  y[out_angle] = theta;
  y[out_speed] = omega;
  y[out_lift] = p.s;
  y[out_lift_d1] = p.s_d1;
  y[out_lift_d2] = p.s_d2;
  y[out_pressure_angle] = pressure_angle(p.s, p.s_d1, params_.pitch_radius, params_.eccentricity);
  y[out_shaft_torque] = torque;
  y[out_drive_power] = torque * omega;
  y[out_acceleration] = omega_dot;
}

}  // namespace mechsim::models::cam
