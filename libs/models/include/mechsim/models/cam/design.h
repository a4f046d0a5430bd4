// The cam design analysis (spec cam.md §7) in one call: everything `mechsim cam-design`
// reports, as plain numbers in SI units (angles in rad). The pieces are also usable on
// their own (geometry_analysis.h, force_analysis.h, flexible_follower.h, flat_face.h).
#pragma once

#include <numbers>
#include <vector>

#include "mechsim/models/cam/flexible_follower.h"
#include "mechsim/models/cam/force_analysis.h"
#include "mechsim/models/cam/geometry_analysis.h"
#include "mechsim/models/cam/motion_law.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::models::cam {

struct CamDesignInput {
  std::vector<Segment> segments;
  CamGeometry geometry;
  double speed_rad_s;                    // constant design speed ω_avg
  follower::FollowerParams follower;     // mass, spring {k, F0}, functional loads
  double pressure_angle_limit_rad = 30.0 * std::numbers::pi / 180.0;
  double speed_fluctuation = 0.1;        // K
  double flywheel_density_kg_m3 = 7800.0;
  double flywheel_thickness_m = 0.05;
  double lambda = 9.38;                  // natural periods in the critical event
  double damping_ratio = 0.08;
  int multi_rise_cycles = 20;
  int steps_per_period = 200;            // RK4 steps per natural period
  int critical_event = -1;               // index into the events, −1: the shortest
};

struct CamDesignReport {
  Continuity continuity;
  PressureAngleExtremes pressure_angle;
  bool pressure_angle_within_limit;      // max |α| < limit
  CurvatureAnalysis curvature;           // per piece, undercut verdict
  OptimalEccentricity optimal_eccentricity;
  ContactForceExtremes contact_force;                 // with the spring
  ContactForceExtremes contact_force_without_spring;
  SpringSizing minimum_spring;           // for the given preload F0
  LiftOffSpeed lift_off;                 // kinetostatic (rigid follower)
  TorqueAnalysis torque;                 // mean power, A(θ) extremes, A_max
  FlywheelDesign flywheel;
  std::vector<RestToRestEvent> events;
  std::size_t critical_event;
  double critical_event_duration_s;      // t1 = β/ω
  double follower_stiffness_n_per_m;     // k_f
  double lambda_prime;                   // λ'
  SingleRiseResult single_rise;
  MultiRiseResult multi_rise;
};

// Throws std::invalid_argument for an invalid law, geometry or follower.
CamDesignReport analyse_cam_design(const CamDesignInput& input);

}  // namespace mechsim::models::cam
