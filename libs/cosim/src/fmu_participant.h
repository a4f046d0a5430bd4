// A participant whose model is an FMU in place of its node type's native block
// (`fmu: {file, interface, step, parameters}` under a participant; docs/fmi.md "An FMU in
// place of a native participant"). The node type still names the participant's topic and
// what it reads, so the FMU must provide the native block's ports by name, with the same
// units: every output the topic publishes and every input the native block requires.
#pragma once

#include <memory>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/catalog.h"
#include "mechsim/models/block.h"

namespace mechsim::cosim {

// Builds the FMU's block for `spec` (which has an `fmu:` section), checked against `native`,
// the block the node type builds from the participant's params. Throws config::ConfigError
// naming the scene file and key for every refusal (the FMU's own, e.g. a missing binary,
// included).
std::unique_ptr<models::Block> make_fmu_block(const config::Scene& scene, const config::ParticipantSpec& spec,
                                              const NodeType& type, const models::Block& native,
                                              const config::ConfigNode* coupling);

}  // namespace mechsim::cosim
