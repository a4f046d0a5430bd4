#include "mechsim/transport/messages.h"

namespace mechsim::transport {

const char* to_string(NodeState s) {
  switch (s) {
    case NodeState::starting: return "starting";
    case NodeState::ready: return "ready";
    case NodeState::running: return "running";
    case NodeState::done: return "done";
    case NodeState::failed: return "failed";
  }
  return "unknown";
}

}  // namespace mechsim::transport
