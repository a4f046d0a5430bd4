// Parsing of the `cvt` node type's `params:` into the CVT model's parameter struct and its
// clamping setting, shared by the operating-map analysis (`mechsim cvt-map`) and, later, the
// `cvt` participant, so that a scene means the same to both. Every key is optional with the
// thesis rig's value (spec cvt.md §6.1) as default; docs/cvt.md lists them. Errors are
// config::ConfigError naming the file and the key path.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/config_node.h"
#include "mechsim/models/cvt/cvt_block.h"
#include "mechsim/models/cvt/cvt_model.h"

namespace mechsim::cosim {

struct CvtConfig {
  models::cvt::CvtParams params;
  models::cvt::ClampMode clamp = models::cvt::ClampMode::safety_factor;
  double safety_factor = 1.0;  // v_K (clamp == safety_factor)
  double clamping_force = 0.0; // F_K [N] (clamp == clamping_force)
  models::cvt::Level level = models::cvt::Level::L1;
};

// `other_keys`: keys of the same map that belong to the caller (e.g. a node's drive and
// dynamics), accepted and left alone.
CvtConfig parse_cvt_config(const config::ConfigNode& params, const std::vector<std::string>& other_keys = {});

// The keys of the `cvt` participant's params that belong to the time run, not to the belt
// (accepted and ignored by `mechsim cvt-map`, so one scene serves both).
const std::vector<std::string>& cvt_time_run_keys();

// The `cvt` participant's params (node_types/cvt.cpp): the belt keys above plus the time run's
// drive, inertias, initial state, ratio actuator and shape table (docs/press-line.md).
models::cvt::CvtBlockParams parse_cvt_block_params(const config::ConfigNode& params);

}  // namespace mechsim::cosim
