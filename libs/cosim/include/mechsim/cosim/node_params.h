// Parsing of the node types' `params:` into the models' parameter structs, shared by the
// node catalog (time simulation) and the analyses (`mechsim cam-design`, ...), so that a
// scene means the same thing to both. Errors are config::ConfigError with the key path.
#pragma once

#include "mechsim/config/config_node.h"
#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::cosim {

models::cam::MotionLaw parse_motion_law(const config::ConfigNode& law);
models::cam::CamShaftParams parse_cam_shaft_params(const config::ConfigNode& params);

struct FollowerConfig {
  std::string model = "rigid";         // rigid
  models::follower::FollowerParams params;
  double roller_radius = 0.0;          // m; 0 = not given (a point follower)
};
FollowerConfig parse_follower_params(const config::ConfigNode& params);

}  // namespace mechsim::cosim
