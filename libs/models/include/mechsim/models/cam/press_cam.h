// The press cam of the report (spec cam.md §1–§3), in one place so that tests, scenes and
// the design analysis use the same numbers.
#pragma once

#include <numbers>
#include <vector>

#include "mechsim/models/cam/motion_law.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::models::cam {

// Dwell 0–26.25°, C1 26.25–45° (+5 mm), C2 45–120° (+20 mm), dwell 120–140°,
// full cycloid 140–210° (−25 mm), dwell 210–360°.
std::vector<Segment> press_cam_segments();

// Functional loads: 45–100° +100 N, 100–120° −230 N, 180–210° −120 N.
std::vector<follower::FunctionalLoad> press_cam_loads();

struct PressCam {
  std::vector<Segment> segments = press_cam_segments();
  double pitch_radius_m = 0.065;   // R0
  double roller_radius_m = 0.035;  // Rr (base radius R0 − Rr = 30 mm)
  double eccentricity_m = 0.0;
  double speed_rad_s = std::numbers::pi;  // cycle time 2 s (30 rpm)
  // m = 25 kg; spring k = 9 N/mm, F0 = 125 N (the report's design).
  follower::FollowerParams follower{25.0, {9000.0, 125.0}, press_cam_loads()};

  MotionLaw law() const { return MotionLaw(segments); }
};

}  // namespace mechsim::models::cam
