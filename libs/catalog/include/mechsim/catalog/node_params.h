// Parsing of the node types' `params:` into the models' parameter structs, shared by the
// node catalog (time simulation) and the analyses (`mechsim cam-design`, ...), so that a
// scene means the same thing to both. Errors are config::ConfigError with the key path.
// The keys are documented in docs/cam-dynamics.md (drive, flywheel, flexible follower).
#pragma once

#include "mechsim/config/config_node.h"
#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/follower/flexible_follower_block.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::cosim {

models::cam::MotionLaw parse_motion_law(const config::ConfigNode& law);
// `speed` of the result is the constant speed, or with a torque drive (drive.type
// constant_torque / motor_line) the nominal speed that the design analyses use; the drive,
// the total shaft inertia (inertia + flywheel) and the initial speed come with it.
models::cam::CamShaftParams parse_cam_shaft_params(const config::ConfigNode& params);

struct FollowerConfig {
  std::string model = "rigid";         // rigid | flexible
  models::follower::FollowerParams params;
  double roller_radius = 0.0;          // m; 0 = not given (a point follower)
  // model: flexible only (params.flexible): follower stiffness k_f, dampers, start lift.
  models::follower::FollowerContact contact;
  double initial_lift = 0.0;           // m
  models::follower::FlexibleFollowerParams flexible() const { return {params, contact, initial_lift}; }
};
FollowerConfig parse_follower_params(const config::ConfigNode& params);

}  // namespace mechsim::cosim
