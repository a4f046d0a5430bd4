#include "mechsim/catalog/catalog.h"

namespace mechsim::cosim {

const InputGroup* NodeType::group_for(const transport::TopicType& t) const {
  for (const auto& g : accepts)
    if (g.topic_type == &t) return &g;
  return nullptr;
}

const std::vector<NodeType>& node_types() {
  static const std::vector<NodeType> types{cam_shaft_node_type(), follower_node_type(), servo_amplifier_node_type(),
                                              tachometer_node_type(), slide_node_type(), cvt_node_type()};
  return types;
}

const NodeType* find_node_type(const std::string& name) {
  for (const auto& t : node_types())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace mechsim::cosim
