// Position setpoint of the NC interpolator (spec nc_slide.md §3): a step, a ramp at constant
// velocity, or a trapezoidal move with velocity and acceleration limits (a triangle when
// the distance is too short to reach the velocity). Slide position in metres, signed.
#pragma once

#include <vector>

namespace mechsim::models::nc {

enum class SetpointKind { step, ramp, trapezoid };

struct SetpointProfile {
  SetpointKind kind = SetpointKind::step;
  double start_time = 0.0;    // [s]
  double distance = 1e-4;     // travel, signed [m]
  double velocity = 0.1;      // ramp / trapezoid velocity limit, > 0 [m/s]
  double acceleration = 1.0;  // trapezoid acceleration limit, > 0 [m/s²]

  // Checks the limits; throws std::invalid_argument naming the bad value.
  void validate() const;
  double position(double t) const;  // [m]
  double velocity_at(double t) const;  // d position/dt [m/s]; 0 for a step (the jump is not a velocity)
  double move_duration() const;     // from start_time to rest at the target [s]
  // Where position or velocity is not smooth: the start (a jump for a step), the end of the
  // ramp, the trapezoid's ends of acceleration and deceleration [s], in time order.
  std::vector<double> corners() const;
};

}  // namespace mechsim::models::nc
