// What the two hosts of node processes (process_host.h on this machine, agent_host.h on
// others) share: a process runs one node or a process group's several (its `members`), and
// the supervisor speaks of nodes, not processes. `Process` is LocalProcess or RemoteNode:
// anything with a `name` (the process's) and `members`.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "mechsim/cosim/node_host.h"
#include "node_processes.h"

namespace mechsim::launch {

// The process that runs `node`, or nullptr.
template <class Process>
const Process* process_running(const std::vector<Process>& processes, const std::string& node) {
  for (const auto& p : processes)
    if (std::find(p.members.begin(), p.members.end(), node) != p.members.end()) return &p;
  return nullptr;
}

// Every node of the processes, in start order.
template <class Process>
std::vector<std::string> nodes_of(const std::vector<Process>& processes) {
  std::vector<std::string> out;
  for (const auto& p : processes) out.insert(out.end(), p.members.begin(), p.members.end());
  return out;
}

// A process that stopped stops every node in it: one NodeExit per member, from the
// process's exit code or signal.
template <class Process>
std::vector<cosim::NodeExit> node_exits(const std::vector<Process>& processes, const std::vector<hostrun::NodeProcess*>& stopped) {
  std::vector<cosim::NodeExit> out;
  for (const hostrun::NodeProcess* s : stopped)
    for (const auto& p : processes)
      if (p.name == s->name)
        for (const auto& member : p.members) {
          out.push_back(cosim::node_exit(member, s->exit_code, s->signalled));
          out.back().reached_end = s->remote_reached_end;
        }
  return out;
}

}  // namespace mechsim::launch
