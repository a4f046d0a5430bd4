// The nodes an agent starts on another host (cosim/node_host.h, agent_client.h): started
// with the same arguments as a local node, watched through the agent's exit reports and
// the nodes' statuses (a silent one is unreachable after the partition grace, not hung),
// stopped through the agent. Not restarted: a restart with rollback is local only. A process
// may be a group (`process: <group>`): one agent process, "process-<group>", several nodes.
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "agent_client.h"
#include "mechsim/cosim/node_host.h"
#include "node_processes.h"

namespace mechsim::launch {

struct RemoteNode {
  std::string name;     // the process: the participant, or "process-<group>"
  std::vector<std::string> members;  // the participants it runs
  std::string host;     // the scene's name of the host
  std::string address;  // its agent's address
  std::string type;     // the node type, or hostrun::kGroupType for a group
  std::string request;  // the start text (JSON, agent_protocol.h)
};

class AgentNodeHost : public cosim::NodeHost {
 public:
  // `agents` outlives this host.
  AgentNodeHost(hostrun::AgentClient& agents, std::vector<RemoteNode> nodes) : agents_(agents), planned_(std::move(nodes)) {}

  std::vector<std::string> nodes() const override;
  void start_all() override;
  std::vector<cosim::NodeExit> poll() override;
  bool exited(const std::string& node) const override { return processes_.find(planned(node).name).exited; }
  std::string describe_exit(const std::string& node) const override { return processes_.find(planned(node).name).describe_exit(); }
  bool remote(const std::string&) const override { return true; }
  std::string placement(const std::string& node) const override;
  void request_stop() override;
  void stop_all(double grace_s) override;
  void pump() override { agents_.pump(); }
  // The file name, in the run folder, of the log the agent streams for `node`'s process.
  std::string log_name(const std::string& node) const { return planned(node).name + ".log"; }

 private:
  const RemoteNode& planned(const std::string& node) const;
  hostrun::AgentClient& agents_;
  std::vector<RemoteNode> planned_;
  hostrun::NodeProcesses processes_;
  std::chrono::steady_clock::time_point stop_requested_{};
};

}  // namespace mechsim::launch
