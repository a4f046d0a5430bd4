// Rigid-follower force, spring, power and flywheel analyses over a cycle at constant
// shaft speed (spec cam.md §3, §4, §7).
//
// The cycle is cut where the law changes piece or a functional load switches; on each
// smooth span extremes are found by sampling and refinement, and a value at the right end
// of a span is the left-hand limit there (a load that ends at b acts up to b⁻).
#pragma once

#include <vector>

#include "mechsim/models/cam/geometry_analysis.h"
#include "mechsim/models/cam/motion_law.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::models::cam {

struct ForceExtremum {
  double angle_rad;
  double lift_m;
  double contact_force_n;
};

struct ContactForceExtremes {
  ForceExtremum min, max;
  bool contact_everywhere;  // N ≥ 0 over the whole cycle
};

// N(θ) extremes at shaft speed ω. Call it with follower.spring = {} for "without spring".
ContactForceExtremes contact_force_extremes(const MotionLaw& law, const CamGeometry& geometry,
                                            const follower::FollowerParams& follower,
                                            double speed_rad_s);

struct SpringSizing {
  // Smallest k with N ≥ 0 everywhere for the given preload:
  // max over θ (S > 0) of (−F_func − F0 − m ω² S'')/S, clamped at 0.
  double min_stiffness_n_per_m;
  double angle_rad;  // where the maximum sits
  double lift_m;
  // False when no stiffness helps: N < 0 where S = 0 (the preload alone is too small).
  bool feasible;
};

SpringSizing minimum_spring_stiffness(const MotionLaw& law, const follower::FollowerParams& follower,
                                      double preload_n, double speed_rad_s);

struct LiftOffSpeed {
  // Lowest ω at which N of §3 becomes negative somewhere (rigid follower, constant speed):
  // ω² = 1 / max over θ of (−m S'')/(F_func + F0 + k S). +inf when the follower never lifts
  // off, 0 when the static forces alone already open the contact.
  double speed_rad_s;
  double angle_rad;
  double lift_m;
};

LiftOffSpeed kinetostatic_lift_off_speed(const MotionLaw& law, const follower::FollowerParams& follower);

struct TorqueAnalysis {
  double mean_torque_nm;  // (1/2π) ∮ M dθ with M = (N cos α) S'
  double mean_power_w;    // mean torque · ω
  double max_torque_nm, angle_max_torque_rad;
  double min_torque_nm, angle_min_torque_rad;
  double max_power_w;     // max of M ω
  // A(θ) = ∫₀^θ (M − M_mean) dθ: its extremes and the swing A_max = A(θ_M) − A(θ_m).
  double theta_a_min_rad, a_min_j;
  double theta_a_max_rad, a_max_value_j;
  double a_max_j;  // the swing (the report's A_max)
};

TorqueAnalysis drive_torque_analysis(const MotionLaw& law, const follower::FollowerParams& follower,
                                     double speed_rad_s);

struct FlywheelDesign {
  double inertia_kgm2;          // I = A_max/(K ω_avg²)
  double disc_radius_m;         // R = (2I/(π t ρ))^(1/4)
  // With a constant drive torque equal to the mean the kinetic energy is E0 − A(θ): the
  // shaft is fastest at argmin A and slowest at argmax A.
  double speed_max_rad_s, theta_speed_max_rad;  // ω_avg (1 + K/2) at θ_a_min
  double speed_min_rad_s, theta_speed_min_rad;  // ω_avg (1 − K/2) at θ_a_max
};

FlywheelDesign flywheel_design(const TorqueAnalysis& torque, double speed_fluctuation,
                               double average_speed_rad_s, double density_kg_m3, double thickness_m);

// One sample of the cycle for plots (motion law, pressure angle, forces, torque with mean).
struct CycleSample {
  double theta_rad;
  double lift_m, lift_d1, lift_d2;
  double pressure_angle_rad;
  double functional_load_n, spring_force_n, inertia_force_n;
  double contact_force_n;
  double contact_force_without_spring_n;
  double drive_torque_nm;
  double a_j;  // A(θ)
};

// `count` equally spaced samples over [0, 2π); A(θ) integrated between them exactly enough
// for plots (5-point Gauss–Legendre per sub-interval, pieces and load switches respected).
std::vector<CycleSample> sample_cycle(const MotionLaw& law, const CamGeometry& geometry,
                                      const follower::FollowerParams& follower, double speed_rad_s,
                                      int count);

}  // namespace mechsim::models::cam
