// A node's failure with its kind, for the typed error of its last status
// (transport::NodeError); what() words it for people (the status message and the log).
#pragma once

#include <stdexcept>
#include <string>

#include "mechsim/transport/messages.h"

namespace mechsim::cosim {

class NodeFailure : public std::runtime_error {
 public:
  NodeFailure(transport::NodeError kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  transport::NodeError kind() const { return kind_; }

 private:
  transport::NodeError kind_;
};

}  // namespace mechsim::cosim
