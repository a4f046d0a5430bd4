// The plan of a cut joined by the interface-Jacobian scheme (scene_plan.cpp's edge pass hands
// it every connection whose coupling element names that scheme).
#pragma once

#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::cosim::coupling {

// Both sides of the connection `c`: the node types must offer a cut port each, one loaded and
// one driven by the torque; each node gets its PlannedCut. Throws config::ConfigError.
void plan_interface_jacobian_cut(const config::Scene& scene, const config::ConnectionSpec& c, PlannedNode& from,
                                 PlannedNode& to);

}  // namespace mechsim::cosim::coupling
