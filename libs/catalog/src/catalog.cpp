#include "mechsim/catalog/catalog.h"

namespace mechsim::cosim {

// The native node types, in the order `mechsim check` lists them: one word each. For a
// word w, the file node_types/<w>.cpp defines `NodeType w_node_type()`, and nodes/CMakeLists.txt
// names w among the executables (docs/new-participant.md).
#define MECHSIM_NATIVE_NODE_TYPES(X) \
  X(cam_shaft) X(follower) X(servo_amplifier) X(tachometer) X(slide) X(cvt) X(linear_scale)

#define MECHSIM_DECLARE_NODE_TYPE(w) NodeType w##_node_type();
MECHSIM_NATIVE_NODE_TYPES(MECHSIM_DECLARE_NODE_TYPE)
#undef MECHSIM_DECLARE_NODE_TYPE

const InputGroup* NodeType::group_for(const transport::TopicType& t) const {
  for (const auto& g : accepts)
    if (g.topic_type == &t) return &g;
  return nullptr;
}

const std::vector<NodeType>& node_types() {
#define MECHSIM_NODE_TYPE_ENTRY(w) w##_node_type(),
  static const std::vector<NodeType> types{MECHSIM_NATIVE_NODE_TYPES(MECHSIM_NODE_TYPE_ENTRY)};
#undef MECHSIM_NODE_TYPE_ENTRY
  return types;
}

const NodeType* find_node_type(const std::string& name) {
  for (const auto& t : node_types())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace mechsim::cosim
