// Binding of the transport-neutral topic types to the fastddsgen-generated C++ classes.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "mechsim/transport/messages.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::transport::fastdds {

// One sample of a data topic type: the generated object plus its copy to and from the
// header + flat doubles the nodes see (booleans as 0/1).
class FastSample {
 public:
  virtual ~FastSample() = default;
  virtual void* data() = 0;  // the generated object, for DataWriter::write / take_next_sample
  virtual void store(const SampleHeader& header, std::span<const double> values) = 0;
  virtual void load(SampleHeader& header, std::vector<double>& values) = 0;
};

class FastType {
 public:
  virtual ~FastType() = default;
  virtual const TopicType& topic_type() const = 0;
  // A new instance of the generated PubSubType (TypeSupport takes ownership).
  virtual eprosima::fastdds::dds::TopicDataType* make_type_support() const = 0;
  virtual std::unique_ptr<FastSample> make_sample() const = 0;
};

// Throws std::runtime_error when the type has no Fast DDS binding.
const FastType& fast_type(const TopicType& type);

}  // namespace mechsim::transport::fastdds
