#include "process_host.h"

#include <stdexcept>

#include "process_members.h"

namespace mechsim::launch {

const LocalProcess& ProcessNodeHost::planned(const std::string& node) const {
  if (const LocalProcess* p = process_running(planned_, node)) return *p;
  throw std::logic_error("no node process runs node '" + node + "'");
}

std::vector<std::string> ProcessNodeHost::nodes() const { return nodes_of(planned_); }

void ProcessNodeHost::start_all() {
  for (const auto& p : planned_) processes_.start(p.name, p.executable, p.command_line.to_arguments(), p.log_path, p.environment);
}

std::vector<cosim::NodeExit> ProcessNodeHost::poll() { return node_exits(planned_, processes_.poll()); }

bool ProcessNodeHost::exited(const std::string& node) const {
  return processes_.find(planned(node).name).exited;
}

std::string ProcessNodeHost::describe_exit(const std::string& node) const {
  return processes_.find(planned(node).name).describe_exit();
}

void ProcessNodeHost::restart(const std::string& node, std::uint64_t step, std::int32_t generation) {
  const LocalProcess& p = planned(node);
  if (!processes_.find(p.name).exited) return;  // a member of a group already started again
  cosim::NodeCommandLine resumed = p.command_line;
  resumed.resume_step = step;
  resumed.generation = generation;
  processes_.restart(p.name, resumed.to_arguments(), p.log_path, p.environment);
}

void ProcessNodeHost::request_stop() {
  // The stop itself (SIGTERM, then SIGKILL after the grace) is stop_all's.
}

}  // namespace mechsim::launch
