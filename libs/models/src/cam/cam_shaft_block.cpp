#include "mechsim/models/cam/cam_shaft_block.h"

#include <cmath>
#include <stdexcept>

#include "mechsim/models/cam/geometry.h"

namespace mechsim::models::cam {

namespace {
// Port indices, fixed by the declaration order in the constructor.
enum Input { in_load_torque };
enum Output { out_angle, out_speed, out_lift, out_lift_d1, out_lift_d2, out_pressure_angle,
              out_shaft_torque, out_drive_power };
}  // namespace

CamShaftBlock::CamShaftBlock(CamShaftParams params) : Block("cam_shaft"), params_(std::move(params)) {
  if (!(params_.pitch_radius > 0.0)) throw std::invalid_argument("cam_shaft: pitch radius must be > 0");
  if (!(std::abs(params_.eccentricity) < params_.pitch_radius))
    throw std::invalid_argument("cam_shaft: |eccentricity| must be smaller than the pitch radius");
  if (!std::isfinite(params_.speed) || !std::isfinite(params_.initial_angle))
    throw std::invalid_argument("cam_shaft: speed and initial angle must be finite");
  const int load = declare_input("load_torque", "N*m", 0.0);
  declare_output("angle", "rad");
  declare_output("speed", "rad/s");
  declare_output("lift", "m");
  declare_output("lift_d1", "m/rad");
  declare_output("lift_d2", "m/rad^2");
  declare_output("pressure_angle", "rad");
  declare_output("shaft_torque", "N*m", {load});
  declare_output("drive_power", "W", {load});
}

void CamShaftBlock::calc_outputs(double t, std::span<const double>, std::span<const double> u,
                                 std::span<double> y) const {
  // Constant speed: the angle is a function of time, not an integrated state, so every
  // process (and the reference) computes bit-identical angles at the same t. Integrating
  // it would let rounding decide on which side of a load boundary a sample falls.
  const double theta = params_.initial_angle + params_.speed * t;
  const LawPoint p = params_.law.evaluate(theta);
  y[out_angle] = theta;
  y[out_speed] = params_.speed;
  y[out_lift] = p.s;
  y[out_lift_d1] = p.s_d1;
  y[out_lift_d2] = p.s_d2;
  y[out_pressure_angle] = pressure_angle(p.s, p.s_d1, params_.pitch_radius, params_.eccentricity);
  y[out_shaft_torque] = u[in_load_torque];
  y[out_drive_power] = u[in_load_torque] * params_.speed;
}

}  // namespace mechsim::models::cam
