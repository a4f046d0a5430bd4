// Binding of the transport-neutral topic types to the idlc-generated C structs.
#pragma once

#include <cstddef>
#include <vector>

#include "dds/dds.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::transport::cyclone {

struct FieldSlot {
  std::size_t offset;
  FieldKind kind;
};

struct CycloneType {
  const TopicType* type;
  const dds_topic_descriptor_t* descriptor;
  std::size_t size;                  // sizeof the generated struct
  std::vector<FieldSlot> slots;      // one per field of `type`, in order
};

// Throws std::runtime_error when the type has no Cyclone binding.
const CycloneType& cyclone_type(const TopicType& type);

}  // namespace mechsim::transport::cyclone
