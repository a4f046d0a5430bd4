#include "agent_host.h"

#include <algorithm>
#include <stdexcept>

namespace mechsim::launch {

const RemoteNode& AgentNodeHost::planned(const std::string& node) const {
  for (const auto& n : planned_)
    if (std::find(n.members.begin(), n.members.end(), node) != n.members.end()) return n;
  throw std::logic_error("no agent's process runs node '" + node + "'");
}

std::vector<std::string> AgentNodeHost::nodes() const {
  std::vector<std::string> out;
  for (const auto& n : planned_) out.insert(out.end(), n.members.begin(), n.members.end());
  return out;
}

void AgentNodeHost::start_all() {
  for (const auto& n : planned_) processes_.start_remote(n.name, n.address, n.request, agents_);
}

std::vector<cosim::NodeExit> AgentNodeHost::poll() {
  std::vector<cosim::NodeExit> out;
  for (const hostrun::NodeProcess* p : processes_.poll())
    for (const auto& n : planned_)
      if (n.name == p->name)
        for (const auto& member : n.members) out.push_back(cosim::node_exit(member, p->exit_code, p->signalled));
  return out;
}

std::string AgentNodeHost::placement(const std::string& node) const {
  for (const auto& n : planned_)
    if (std::find(n.members.begin(), n.members.end(), node) != n.members.end()) return "on host " + n.host + " (" + n.address + ")";
  return {};
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
