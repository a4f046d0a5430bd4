#include "process_host.h"

#include <stdexcept>

namespace mechsim::launch {

const LocalProcess& ProcessNodeHost::planned(const std::string& node) const {
  for (const auto& p : planned_)
    for (const auto& m : p.members)
      if (m == node) return p;
  throw std::logic_error("no node process runs node '" + node + "'");
}

std::vector<std::string> ProcessNodeHost::nodes() const {
  std::vector<std::string> out;
  for (const auto& p : planned_) out.insert(out.end(), p.members.begin(), p.members.end());
  return out;
}

void ProcessNodeHost::start_all() {
  for (const auto& p : planned_) processes_.start(p.name, p.executable, p.args, p.log_path, p.environment);
}

std::vector<cosim::NodeExit> ProcessNodeHost::poll() {
  std::vector<cosim::NodeExit> out;
  for (const hostrun::NodeProcess* p : processes_.poll())
    for (const auto& planned : planned_)
      if (planned.name == p->name)
        for (const auto& member : planned.members) out.push_back(cosim::node_exit(member, p->exit_code, p->signalled));
  return out;
}

bool ProcessNodeHost::exited(const std::string& node) const {
  return processes_.find(planned(node).name).exited;
}

std::string ProcessNodeHost::describe_exit(const std::string& node) const {
  return processes_.find(planned(node).name).describe_exit();
}

void ProcessNodeHost::restart(const std::string& node, std::uint64_t step, std::int32_t generation) {
  const LocalProcess& p = planned(node);
  if (!processes_.find(p.name).exited) return;  // a member of a group already started again
  std::vector<std::string> args = p.args;
  args.insert(args.end(), {"--resume", std::to_string(step), "--generation", std::to_string(generation)});
  processes_.restart(p.name, args, p.log_path, p.environment);
}

void ProcessNodeHost::request_stop() {
  // The stop itself (SIGTERM, then SIGKILL after the grace) is stop_all's.
}

}  // namespace mechsim::launch
