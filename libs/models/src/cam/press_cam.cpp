#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {

std::vector<Segment> press_cam_segments() {
  const double c2_span = deg_to_rad(75.0), c2_lift = 0.020, c1_lift = 0.005;
  const double c1_span = matched_c1_span(c1_lift, c2_span, c2_lift);  // 18.75°
  const double c2_start = deg_to_rad(45.0);
  return {
      {SegmentType::half_cycloid_c1, c2_start - c1_span, c1_span, c1_lift},
      {SegmentType::half_cycloid_c2, c2_start, c2_span, c2_lift},
      {SegmentType::full_cycloid, deg_to_rad(140.0), deg_to_rad(70.0), -0.025},
  };
}

std::vector<follower::FunctionalLoad> press_cam_loads() {
  return {
      {deg_to_rad(45.0), deg_to_rad(100.0), 100.0},
      {deg_to_rad(100.0), deg_to_rad(120.0), -230.0},
      {deg_to_rad(180.0), deg_to_rad(210.0), -120.0},
  };
}

}  // namespace mechsim::models::cam
