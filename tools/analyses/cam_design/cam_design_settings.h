// The `design:` section of a scene: the settings of `mechsim cam-design` (docs/cam-design.md).
// Every key is optional and defaults to the report's value; bad input is a
// config::ConfigError naming the file and the key path (design.flywheel.thickness, ...).
#pragma once

#include <numbers>
#include <optional>

#include "mechsim/config/config_node.h"
#include "mechsim/models/cam/flat_face.h"

namespace mechsim::tools::cam_design {

enum class FollowerKind {
  roller,     // the scene's cam_shaft and follower participants (spec §1–§5)
  flat_face,  // the exercise of spec §6, described in design.flat_face
};

struct DesignSettings {
  double speed_fluctuation = 0.1;         // K = (ω_max − ω_min)/ω_avg
  double flywheel_density_kg_m3 = 7800.0;
  double flywheel_thickness_m = 0.05;
  double lambda = 9.38;                   // natural periods in the critical event
  double damping_ratio = 0.08;
  int multi_rise_cycles = 20;
  double pressure_angle_limit_rad = 30.0 * std::numbers::pi / 180.0;
  bool match_c1_to_c2 = false;            // report β1 of the first C1 matched to its C2
  FollowerKind follower = FollowerKind::roller;
  // Only with follower == flat_face: h, β, R_b, m, k, k x0, ω of the exercise.
  std::optional<models::cam::FlatFaceParams> flat_face;
};

// `design` is Scene::design (absent: all defaults).
DesignSettings parse_design_settings(const std::optional<config::ConfigNode>& design);

}  // namespace mechsim::tools::cam_design
