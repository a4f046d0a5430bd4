// The coupling element of a connection as the scene writes it (`coupling: {scheme,
// stiffness, damping, levels}`), parsed once: the node types on both sides, the plan of the
// cut and the NC analyses read this.
#pragma once

#include "mechsim/config/config_node.h"
#include "mechsim/catalog/coupling/scheme.h"
#include "mechsim/models/nc/coupling.h"

namespace mechsim::cosim::coupling {

struct CouplingSpec {
  CouplingScheme scheme = CouplingScheme::compliant;
  models::nc::CouplingParams params;
  int levels = 10;  // interface_jacobian: torque levels per macro step (1..kMaxLevels)
};
// Throws config::ConfigError naming the key (an unknown scheme lists the known ones).
CouplingSpec parse_coupling(const config::ConfigNode& coupling);

}  // namespace mechsim::cosim::coupling
