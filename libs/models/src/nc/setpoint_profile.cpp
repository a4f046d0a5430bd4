#include "mechsim/models/nc/setpoint_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mechsim::models::nc {

namespace {

// Unsigned trapezoid: acceleration phase t_a, constant-velocity phase t_c, peak velocity.
struct Trapezoid {
  double accel_time, cruise_time, peak_velocity;
};

Trapezoid trapezoid(const SetpointProfile& p) {
  const double d = std::abs(p.distance), a = p.acceleration;
  double v = p.velocity;
  if (d < v * v / a) v = std::sqrt(d * a);  // triangle: the velocity limit is not reached
  const double accel_time = v / a;
  return {accel_time, v > 0 ? (d - v * accel_time) / v : 0.0, v};
}

}  // namespace

void SetpointProfile::validate() const {
  if (kind != SetpointKind::step && !(velocity > 0))
    throw std::invalid_argument("setpoint: velocity must be > 0");
  if (kind == SetpointKind::trapezoid && !(acceleration > 0))
    throw std::invalid_argument("setpoint: acceleration must be > 0");
}

std::vector<double> SetpointProfile::corners() const {
  switch (kind) {
    case SetpointKind::step: return {start_time};
    case SetpointKind::ramp: return {start_time, start_time + move_duration()};
    case SetpointKind::trapezoid: {
      const Trapezoid tr = trapezoid(*this);
      std::vector<double> at{start_time, start_time + tr.accel_time};
      // A triangle has no cruise (its computed cruise time is zero up to rounding).
      if (tr.cruise_time > 1e-9 * tr.accel_time) at.push_back(start_time + tr.accel_time + tr.cruise_time);
      at.push_back(start_time + move_duration());
      return at;
    }
  }
  return {};
}

double SetpointProfile::move_duration() const {
  switch (kind) {
    case SetpointKind::step: return 0.0;
    case SetpointKind::ramp: return std::abs(distance) / velocity;
    case SetpointKind::trapezoid: {
      const Trapezoid tr = trapezoid(*this);
      return 2 * tr.accel_time + tr.cruise_time;
    }
  }
  return 0.0;
}

double SetpointProfile::position(double t) const {
  const double tau = t - start_time;
  if (tau < 0) return 0.0;
  const double sign = distance < 0 ? -1.0 : 1.0, d = std::abs(distance);
  switch (kind) {
    case SetpointKind::step: return distance;
    case SetpointKind::ramp: return sign * std::min(d, velocity * tau);
    case SetpointKind::trapezoid: {
      const auto [ta, tc, v] = trapezoid(*this);
      const double a = acceleration;
      if (tau < ta) return sign * 0.5 * a * tau * tau;
      if (tau < ta + tc) return sign * (0.5 * v * ta + v * (tau - ta));
      const double tau_end = 2 * ta + tc;
      if (tau < tau_end) return sign * (d - 0.5 * a * (tau_end - tau) * (tau_end - tau));
      return distance;
    }
  }
  return 0.0;
}

double SetpointProfile::velocity_at(double t) const {
  const double tau = t - start_time;
  if (tau < 0) return 0.0;
  const double sign = distance < 0 ? -1.0 : 1.0;
  switch (kind) {
    case SetpointKind::step: return 0.0;
    case SetpointKind::ramp: return velocity * tau < std::abs(distance) ? sign * velocity : 0.0;
    case SetpointKind::trapezoid: {
      const auto [ta, tc, v] = trapezoid(*this);
      if (tau < ta) return sign * acceleration * tau;
      if (tau < ta + tc) return sign * v;
      const double tau_end = 2 * ta + tc;
      if (tau < tau_end) return sign * acceleration * (tau_end - tau);
      return 0.0;
    }
  }
  return 0.0;
}

}  // namespace mechsim::models::nc
