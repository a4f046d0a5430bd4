// An elastic segment of a line shaft (docs/line-shaft.md): a massless torsion spring with a
// parallel damper between an upstream shaft (angle θ_u, speed ω_u) and the shaft it drives
// (θ, ω). The twist q = θ_u − θ; the segment delivers T = k q + c q̇ to the downstream
// shaft and takes the same T from the upstream one (action equals reaction). Its power
// balance, T (ω_u − ω) = d/dt(½ k q²) + c q̇², is what the line's energy balance closes on.
#pragma once

namespace mechsim::models::cam {

struct ShaftSegment {
  double stiffness = 0.0;  // k, N m/rad (> 0)
  double damping = 0.0;    // c, N m s/rad (>= 0)
};

// Throws std::invalid_argument for k <= 0, c < 0 or non-finite values.
void validate(const ShaftSegment& segment);

// Torque the segment delivers to the downstream shaft [N m].
inline double segment_torque(const ShaftSegment& s, double upstream_angle, double upstream_speed, double angle,
                             double speed) {
  return s.stiffness * (upstream_angle - angle) + s.damping * (upstream_speed - speed);
}
// Elastic energy stored at twist q [J].
inline double segment_energy(const ShaftSegment& s, double twist) { return 0.5 * s.stiffness * twist * twist; }
// Power the damper dissipates at twist rate q̇ [W].
inline double segment_damping_power(const ShaftSegment& s, double twist_rate) {
  return s.damping * twist_rate * twist_rate;
}

}  // namespace mechsim::models::cam
