// How the launcher's AgentClient reaches the agents of a run's hosts: one SSH session per
// host (ssh_agent_link.h, the default) or the DDS topics of the standing daemons
// (dds_agent_link). Either carries the messages of agent_protocol.h.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "mechsim/transport/participant.h"

namespace mechsim::hostrun {

class AgentLink {
 public:
  virtual ~AgentLink() = default;
  // To the agent at m.host (kAllAgents: every agent of the link).
  virtual void send(const transport::AgentMessage& m) = 0;
  // The next reply; its host is the address of the agent it came from.
  virtual std::optional<transport::AgentMessage> take() = 0;
  // Whether requests now reach `agents` agents (DDS: readers matched; SSH: sessions open).
  virtual bool reaches(std::size_t agents) const = 0;
  // Blocks until a reply may be there or the timeout passes.
  virtual void wait(std::chrono::milliseconds timeout) = 0;
  // Whether the agent at `address` can no longer answer (its SSH session ended).
  virtual bool gone(const std::string& address) const = 0;
  // Why the agent at `address` does not answer, when the link knows ("" otherwise).
  virtual std::string problem(const std::string& address) const = 0;
};

struct HostLayout;

// The standing DDS daemons of the run's domain (mechsim/agent/request and .../reply).
std::unique_ptr<AgentLink> dds_agent_link(transport::Participant& participant);
// The link `hosts` asks for: an SSH session to each remote host (ssh's stderr in
// <run_dir>/ssh-<host>.log; MECHSIM_SSH overrides the ssh command) or the DDS daemons.
std::unique_ptr<AgentLink> open_agent_link(const HostLayout& hosts, transport::Participant& participant, int domain,
                                           const std::string& run_dir);

}  // namespace mechsim::hostrun
