#include "agent_host.h"

#include <stdexcept>

#include "process_members.h"

namespace mechsim::launch {

const RemoteNode& AgentNodeHost::planned(const std::string& node) const {
  if (const RemoteNode* n = process_running(planned_, node)) return *n;
  throw std::logic_error("no agent's process runs node '" + node + "'");
}

std::vector<std::string> AgentNodeHost::nodes() const { return nodes_of(planned_); }

void AgentNodeHost::start_all() {
  for (const auto& n : planned_) processes_.start_remote(n.name, n.address, n.request, agents_);
}

std::vector<cosim::NodeExit> AgentNodeHost::poll() { return node_exits(planned_, processes_.poll()); }

std::string AgentNodeHost::placement(const std::string& node) const {
  const RemoteNode* n = process_running(planned_, node);
  return n ? "on host " + n->host + " (" + n->address + ")" : std::string();
}

void AgentNodeHost::request_stop() {
  if (processes_.all_exited()) return;
  agents_.stop_all();
  stop_requested_ = std::chrono::steady_clock::now();
}

void AgentNodeHost::stop_all(double grace_s) {
  // The grace counts from the request, which went out with the local nodes' SIGTERM.
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - stop_requested_).count();
  processes_.stop_all(std::max(0.0, grace_s - waited));
}

}  // namespace mechsim::launch
