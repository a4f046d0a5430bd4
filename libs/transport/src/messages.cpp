#include "mechsim/transport/messages.h"

#include <cstdio>
#include <stdexcept>

#include "mechsim/transport/participant.h"

namespace mechsim::transport {

std::string guid_text(const unsigned char (&guid)[16]) {
  std::string out;
  char b[3];
  for (std::size_t i = 0; i < 16; ++i) {
    std::snprintf(b, sizeof b, "%02x", guid[i]);
    out += b;
    if (i == 11) out += ':';  // GUID prefix : entity id
  }
  return out;
}

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

std::unique_ptr<SampleWriter> Participant::create_redundant_writer(const std::string&, const TopicType&) { return nullptr; }
std::unique_ptr<SampleReader> Participant::create_redundant_reader(const std::string&, const TopicType&) { return nullptr; }

std::unique_ptr<AgentWriter> Participant::create_agent_writer(const std::string& topic) {
  throw std::logic_error("the " + vendor() + " transport has no agent topics (" + topic + "): multi-host runs need a DDS vendor");
}

std::unique_ptr<AgentReader> Participant::create_agent_reader(const std::string& topic) {
  throw std::logic_error("the " + vendor() + " transport has no agent topics (" + topic + "): multi-host runs need a DDS vendor");
}

}  // namespace mechsim::transport
