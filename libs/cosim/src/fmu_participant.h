// A participant whose model is an FMU in place of its node type's native block
// (`fmu: {file, interface, step, parameters}` under a participant; docs/fmi.md "An FMU in
// place of a native participant"). The node type still names the participant's topic and
// what it reads, so the FMU must provide the native block's ports by name, with the same
// units: every output the topic publishes and every input the native block requires.
#pragma once

#include <memory>
#include <string>

#include "mechsim/transport/topic_types.h"

#include "mechsim/config/scene.h"
#include "mechsim/catalog/catalog.h"
#include "mechsim/models/block.h"

namespace mechsim::fmi {
class FmuArchive;
}

namespace mechsim::cosim {

// Builds the FMU's block for `spec` (which has an `fmu:` section), checked against `native`,
// the block the node type builds from the participant's params. Throws config::ConfigError
// naming the scene file and key for every refusal (the FMU's own, e.g. a missing binary,
// included).
std::unique_ptr<models::Block> make_fmu_block(const config::Scene& scene, const config::ParticipantSpec& spec,
                                              const NodeType& type, const models::Block& native,
                                              const config::ConfigNode* coupling);

// `type: fmu`: an FMU with ports of its own; its node type is made for each participant from
// its FMU, so it is not in the catalog's node_types(). Its node executable is `fmu`.
inline constexpr const char* kFmuNodeType = "fmu";

// A participant of `type: fmu` (docs/fmi.md, "FMU participants"): the FMU's block, whose
// ports are its exchanged input and output variables by name, and a node type made for it
// alone, publishing <name>/outputs as FmuOutputs (idl/fmu.idl) with the FMU's outputs as
// the topic type's fields, each in the FMU variable's unit.
struct FmuParticipant {
  std::shared_ptr<const fmi::FmuArchive> archive;
  std::string file;  // as the scene names it, resolved against the scene's folder
  transport::TopicType topic_type;
  NodeType node_type;
};
struct BuiltFmuParticipant {
  std::shared_ptr<const FmuParticipant> participant;
  std::unique_ptr<models::Block> block;
};
// Throws config::ConfigError naming the scene file and key for every refusal.
BuiltFmuParticipant make_fmu_participant(const config::Scene& scene, const config::ParticipantSpec& spec,
                                         const config::ConfigNode* coupling);

// A port-level connection's units: the publisher's field and the subscriber's input must
// be in the same unit (dimension, SI factor and offset); an FMU port's unit comes from its
// <UnitDefinitions>, a native port's from mechsim's unit parser. Refused at `key_path`
// naming both ports and both units.
void check_connection_units(const config::Scene& scene, const std::string& key_path, const std::string& from_port,
                            const std::string& from_unit, const FmuParticipant* from_fmu, const std::string& to_port,
                            const std::string& to_unit, const FmuParticipant* to_fmu);

}  // namespace mechsim::cosim
