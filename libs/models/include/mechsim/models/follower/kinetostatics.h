// Rigid (kinetostatic) follower forces (spec cam.md §3).
//
// Sign convention: a force counts positive when the cam must supply it, i.e. when it acts
// on the follower towards the cam centre (a compressive functional load, the spring, the
// inertia of an accelerating rise). The contact force N is positive while the cam pushes
// the follower away from its centre; N < 0 means the follower lifts off.
//   N cos α = F_func + F0 + k S + m (S'' ω² + S' ω̇)
#pragma once

#include <vector>

namespace mechsim::models::follower {

// A functional load acting over the half-open cam-angle interval [start, end).
struct FunctionalLoad {
  double start_rad;  // in [0, 2π)
  double end_rad;    // in (start, 2π]
  double force_n;    // > 0 compressive (the cam must push), < 0 tensile
  // A ramp: the force runs linearly in the cam angle from force_n at start to end_force_n
  // at end (a forming force that builds up as the die closes). Off: constant force_n.
  bool ramp = false;
  double end_force_n = 0.0;
  double at(double theta_rad) const {
    return ramp ? force_n + (end_force_n - force_n) * (theta_rad - start_rad) / (end_rad - start_rad) : force_n;
  }
};

// Return spring: F = preload + stiffness · S.
struct Spring {
  double stiffness_n_per_m = 0.0;
  double preload_n = 0.0;
};

struct FollowerParams {
  double mass = 0.0;  // equivalent follower mass, kg
  Spring spring;
  std::vector<FunctionalLoad> loads;
};

// Throws std::invalid_argument for a negative mass or stiffness, a load interval outside
// [0, 2π] or with end ≤ start, or overlapping load intervals.
void validate(const FollowerParams& params);

// Sum of the functional loads at the cam angle θ (wrapped into [0, 2π)).
double functional_load(const std::vector<FunctionalLoad>& loads, double theta_rad);
// θ wrapped into [0, 2π), exactly as functional_load() wraps it.
double angle_in_revolution(double theta_rad);
// The ends of the load intervals [rad, in [0, 2π)], each once, ascending: where the load
// jumps (Block::angle_events of the followers).
std::vector<double> load_boundaries(const std::vector<FunctionalLoad>& loads);
// True when θ, wrapped, lies at `boundary` or less than half a revolution past it: the side
// functional_load() treats as after the boundary (its intervals are half-open, [from, to)).
bool angle_at_or_past(double theta_rad, double boundary_rad);

struct FollowerForces {
  double functional_load_n;  // F_func
  double spring_force_n;     // F0 + k S
  double inertia_force_n;    // m (S'' ω² + S' ω̇)
  double normal_component_n; // N cos α: the sum of the three above
  double contact_force_n;    // N
  double drive_torque_nm;    // M = (N cos α) S': the torque the shaft must deliver
  // M without the part m S'² ω̇ that the shaft's acceleration causes: what a dynamic cam
  // shaft receives when it carries the reflected inertia m S'² itself (spec §4).
  double drive_torque_rest_nm;
};

// Forces on the rigid follower at cam angle θ for the follower lift S, S', S'' (m, m/rad,
// m/rad²), pressure angle α, shaft speed ω and shaft acceleration ω̇.
FollowerForces kinetostatic_forces(const FollowerParams& params, double theta_rad, double lift_m,
                                   double lift_d1, double lift_d2, double pressure_angle_rad,
                                   double speed_rad_s, double acceleration_rad_s2 = 0.0);

// Inertia the rigid follower reflects onto the cam shaft, m S'² (kg m²): with a varying
// shaft speed its inertia force m S' ω̇ contributes m S'² ω̇ to the drive torque (spec §4).
double reflected_inertia(double mass_kg, double lift_d1);

}  // namespace mechsim::models::follower
