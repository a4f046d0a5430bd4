#include "mechsim/models/cam/cam_shaft_block.h"

#include <cmath>
#include <stdexcept>

#include "mechsim/models/cam/geometry.h"

namespace mechsim::models::cam {

namespace {
// Port indices, fixed by the declaration order in the constructor.
// The driven modes' inputs follow these two; their indices are members.
enum Input { in_load_torque, in_reflected_inertia };
enum Output { out_angle, out_speed, out_lift, out_lift_d1, out_lift_d2, out_pressure_angle,
              out_shaft_torque, out_drive_power, out_acceleration, out_drive_load_torque,
              out_drive_load_inertia, out_kinetic_energy, out_segment_energy, out_segment_damping_power };
enum State { x_angle, x_speed, x_twist };

// The parameters' own consistency, before any port is declared (std::invalid_argument).
void check_params(const CamShaftParams& p) {
  if (!(p.pitch_radius > 0.0)) throw std::invalid_argument("cam_shaft: pitch radius must be > 0");
  if (!(std::abs(p.eccentricity) < p.pitch_radius))
    throw std::invalid_argument("cam_shaft: |eccentricity| must be smaller than the pitch radius");
  if (!std::isfinite(p.speed) || !std::isfinite(p.initial_angle))
    throw std::invalid_argument("cam_shaft: speed and initial angle must be finite");
  validate(p.drive);
  if (!(p.gear_ratio >= 0.0 && std::isfinite(p.gear_ratio)))
    throw std::invalid_argument("cam_shaft: the gear ratio must be finite and >= 0");
  const bool driven = p.gear_ratio > 0.0;  // CamShaftBlock::is_driven
  if (driven && p.drive.is_torque_source())
    throw std::invalid_argument("cam_shaft: a shaft driven through a gear has no drive torque of its own");
  if (driven && !(p.inertia_kgm2 >= 0.0 && std::isfinite(p.inertia_kgm2)))
    throw std::invalid_argument("cam_shaft: the shaft inertia must be finite and >= 0");
  if (p.segment) {
    validate(*p.segment);
    if (driven || p.drive.is_torque_source())
      throw std::invalid_argument("cam_shaft: a shaft driven through a segment has no gear and no drive torque of its own");
    if (!(p.inertia_kgm2 > 0.0 && std::isfinite(p.inertia_kgm2)))
      throw std::invalid_argument("cam_shaft: a shaft driven through a segment needs a shaft inertia > 0");
    if (p.initial_speed && !std::isfinite(*p.initial_speed))
      throw std::invalid_argument("cam_shaft: the initial speed must be finite");
  }
  const bool dynamic = p.drive.is_torque_source();
  if (dynamic) {
    // Dwells reflect no follower inertia: the shaft's own inertia must carry ω̇ there.
    if (!(p.inertia_kgm2 > 0.0 && std::isfinite(p.inertia_kgm2)))
      throw std::invalid_argument("cam_shaft: a torque drive needs a shaft inertia > 0");
    if (p.initial_speed && !std::isfinite(*p.initial_speed))
      throw std::invalid_argument("cam_shaft: the initial speed must be finite");
  }
}
}  // namespace

CamShaftBlock::CamShaftBlock(CamShaftParams params) : Block("cam_shaft"), params_(std::move(params)) {
  check_params(params_);
  const bool driven = is_driven();
  const bool dynamic = params_.drive.is_torque_source();
  const int load = declare_input("load_torque", "N*m", 0.0);
  const int reflected = declare_input("reflected_inertia", "kg*m^2", 0.0);
  using Ft = std::vector<int>;
  if (is_segment_driven()) {
    in_drive_speed_ = declare_required_input("drive_speed", "rad/s");
    in_downstream_torque_ = declare_input("downstream_torque", "N*m", 0.0);
    const int ds = in_drive_speed_, down = in_downstream_torque_;
    declare_output("angle", "rad");
    declare_output("speed", "rad/s");
    declare_output("lift", "m");
    declare_output("lift_d1", "m/rad");
    declare_output("lift_d2", "m/rad^2");
    declare_output("pressure_angle", "rad");
    declare_output("shaft_torque", "N*m", {ds});
    declare_output("drive_power", "W", {ds});
    declare_output("acceleration", "rad/s^2", {load, reflected, ds, down});
    declare_output("drive_load_torque", "N*m", {ds});
    declare_output("drive_load_inertia", "kg*m^2");
    declare_output("kinetic_energy", "J");
    declare_output("segment_energy", "J");
    declare_output("segment_damping_power", "W", {ds});
    declare_state("angle", "rad");
    declare_state("speed", "rad/s");
    declare_state("twist", "rad");
    return;
  }
  const int dspeed = driven ? (in_drive_speed_ = declare_input("drive_speed", "rad/s", 0.0)) : -1;
  const int daccel = driven ? (in_drive_acceleration_ = declare_input("drive_acceleration", "rad/s^2", 0.0)) : -1;
  const int down = driven ? (in_downstream_torque_ = declare_input("downstream_torque", "N*m", 0.0)) : -1;
  declare_output("angle", "rad");
  declare_output("speed", "rad/s", driven ? Ft{dspeed} : Ft{});
  declare_output("lift", "m");
  declare_output("lift_d1", "m/rad");
  declare_output("lift_d2", "m/rad^2");
  declare_output("pressure_angle", "rad");
  if (driven) {
    declare_output("shaft_torque", "N*m", {load, reflected, daccel, down});
    declare_output("drive_power", "W", {load, reflected, daccel, dspeed, down});
    declare_output("acceleration", "rad/s^2", {daccel});
    declare_output("drive_load_torque", "N*m", {load, down});
    declare_output("drive_load_inertia", "kg*m^2", {reflected});
    declare_output("kinetic_energy", "J", {dspeed});
    declare_state("angle", "rad");
    return;
  }
  declare_output("shaft_torque", "N*m", dynamic ? Ft{} : Ft{load});
  declare_output("drive_power", "W", dynamic ? Ft{} : Ft{load});
  declare_output("acceleration", "rad/s^2", dynamic ? Ft{load, reflected} : Ft{});
  declare_output("drive_load_torque", "N*m");
  declare_output("drive_load_inertia", "kg*m^2");
  declare_output("kinetic_energy", "J");
  if (dynamic) {
    declare_state("angle", "rad");
    declare_state("speed", "rad/s");
  }
}

double CamShaftBlock::angular_acceleration(double speed, double load_torque_rest, double reflected_inertia,
                                           double downstream_torque) const {
  if (!has_dynamic_drive()) return 0.0;
  return (params_.drive.torque_at(speed) - load_torque_rest - downstream_torque) /
         (params_.inertia_kgm2 + reflected_inertia);
}

namespace {
// The driving segment's twist (a state), its rate from the upstream shaft's speed, its torque.
struct SegmentState {
  double twist, twist_rate, torque;
};
SegmentState segment_state(const ShaftSegment& s, double twist, double upstream_speed, double speed) {
  return {twist, upstream_speed - speed, segment_torque(s, twist, upstream_speed, 0.0, speed)};
}
}  // namespace

double CamShaftBlock::segment_acceleration(double segment_torque, std::span<const double> u) const {
  return (segment_torque - u[in_load_torque] - u[in_downstream_torque_]) / (params_.inertia_kgm2 + u[in_reflected_inertia]);
}

void CamShaftBlock::initial_state(double, std::span<double> x) const {
  if (is_driven()) {
    x[x_angle] = params_.initial_angle;
    return;
  }
  if (!has_dynamic_drive() && !is_segment_driven()) return;
  x[x_angle] = params_.initial_angle;
  x[x_speed] = params_.initial_speed.value_or(params_.speed);
  if (is_segment_driven()) x[x_twist] = 0.0;  // the line starts untwisted
}

void CamShaftBlock::derivatives(double, std::span<const double> x, std::span<const double> u,
                                std::span<double> dxdt) const {
  if (is_driven()) {
    dxdt[x_angle] = u[in_drive_speed_] / params_.gear_ratio;
    return;
  }
  if (is_segment_driven()) {
    const SegmentState seg = segment_state(*params_.segment, x[x_twist], u[in_drive_speed_], x[x_speed]);
    dxdt[x_angle] = x[x_speed];
    dxdt[x_speed] = segment_acceleration(seg.torque, u);
    dxdt[x_twist] = seg.twist_rate;
    return;
  }
  if (!has_dynamic_drive()) return;
  dxdt[x_angle] = x[x_speed];
  dxdt[x_speed] = angular_acceleration(x[x_speed], u[in_load_torque], u[in_reflected_inertia]);
}

void CamShaftBlock::calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                                 std::span<double> y) const {
  double theta, omega, omega_dot, torque;
  double load_torque_out = 0.0, load_inertia_out = 0.0;
  if (is_driven()) {
    const double g = params_.gear_ratio;
    const double J = params_.inertia_kgm2 + u[in_reflected_inertia];
    const double load = u[in_load_torque] + u[in_downstream_torque_];
    theta = x[x_angle];
    omega = u[in_drive_speed_] / g;
    omega_dot = u[in_drive_acceleration_] / g;
    torque = load + J * omega_dot;  // what the gear delivers to the cam shaft
    load_torque_out = load / g;
    load_inertia_out = J / (g * g);
  } else if (is_segment_driven()) {
    const SegmentState seg = segment_state(*params_.segment, x[x_twist], u[in_drive_speed_], x[x_speed]);
    theta = x[x_angle];
    omega = x[x_speed];
    omega_dot = segment_acceleration(seg.torque, u);
    torque = seg.torque;
    load_torque_out = seg.torque;  // what the segment takes from the upstream shaft
    y[out_segment_energy] = segment_energy(*params_.segment, seg.twist);
    y[out_segment_damping_power] = segment_damping_power(*params_.segment, seg.twist_rate);
  } else if (has_dynamic_drive()) {
    theta = x[x_angle];
    omega = x[x_speed];
    omega_dot = angular_acceleration(omega, u[in_load_torque], u[in_reflected_inertia]);
    torque = params_.drive.torque_at(omega);
  } else {
    // Constant speed: the angle is a function of time, not an integrated state, so every
    // process (and the reference) computes bit-identical angles at the same t. Integrating
    // it would let rounding decide on which side of a load boundary a sample falls.
    theta = uniform_rotation()->angle(t);
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
  y[out_drive_load_torque] = load_torque_out;
  y[out_drive_load_inertia] = load_inertia_out;
  y[out_kinetic_energy] = 0.5 * params_.inertia_kgm2 * omega * omega;
}

std::optional<Block::UniformRotation> CamShaftBlock::uniform_rotation() const {
  if (is_driven() || is_segment_driven() || has_dynamic_drive()) return std::nullopt;
  return UniformRotation{params_.initial_angle, params_.speed};
}

std::vector<double> CamShaftBlock::angle_law_changes() const {
  std::vector<double> joints;
  for (const auto& piece : params_.law.pieces()) joints.push_back(piece.segment.start_rad);
  return joints;
}

}  // namespace mechsim::models::cam
