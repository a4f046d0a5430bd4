// The node types a scene may name (cam_shaft, follower, ...): for each, how its
// `params:` become a block, which topic type it publishes, and which topic types it can
// subscribe to with the mapping of topic fields onto its block inputs.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mechsim/config/config_node.h"
#include "mechsim/models/block.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::cosim {

// Accepting a topic type as input: field name -> block input name. Pairs whose input the
// block does not declare (its configuration does not use it) are skipped.
struct InputGroup {
  const transport::TopicType* topic_type;
  std::vector<std::pair<std::string, std::string>> field_to_input;
};

// The side of a stiff mechanical cut a node type can take in the interface-Jacobian
// coupling scheme (docs/nc-loop.md): the block input that receives the coupling torque T as
// it is, and the outputs with the interface angle and speed. twist_sign +1: the side that T
// loads (its angle counts positively in the twist: the motor); -1: the side T drives.
struct CutPort {
  std::string torque_input, angle_output, speed_output;
  int twist_sign = 1;
};

struct NodeType {
  std::string name;                       // "cam_shaft"
  std::string summary;                    // one line for --help and docs
  const transport::TopicType* publishes;  // its state topic type
  std::string topic_suffix;               // topic = "<instance>/<suffix>"
  // Parses and validates params (throws config::ConfigError) and builds the block. The
  // block's outputs named like the topic fields are published. `coupling` is the element
  // at the cut of a connection to or from this participant (nullptr when there is none).
  std::function<std::unique_ptr<models::Block>(const config::ConfigNode& params, const config::ConfigNode* coupling)>
      make_block;
  std::vector<InputGroup> accepts;
  // Set when the type can be one side of an interface-Jacobian cut (built in torque mode).
  std::optional<CutPort> cut_port = std::nullopt;

  const InputGroup* group_for(const transport::TopicType& t) const;
};

const std::vector<NodeType>& node_types();
const NodeType* find_node_type(const std::string& name);

// Each type's entry is built in src/node_types/<type>.cpp and registered in src/catalog.cpp.

}  // namespace mechsim::cosim
