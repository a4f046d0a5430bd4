// Where the nodes of a run execute: the one seam the supervisor (supervisor.h) drives.
// Three implementations: node processes on this machine (tools/launch/process_host.h,
// several nodes may share a process: `participants.<p>.process`), node processes an agent
// started on another host (tools/launch/agent_host.h), and threads of this process
// (thread_host.h, what run_inproc and a process group use). The supervisor knows nothing
// of pids, agents or threads: it starts, polls, restarts and stops nodes by name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mechsim::cosim {

// A node's exit code, as a process (node_main) or a thread (run_node). The code carries the
// kind of failure so the supervisor knows it without the node's last status, which travels
// best effort and can be lost on a loaded machine (a divergence gets stable-step advice).
namespace node_exit_code {
constexpr int done = 0;
constexpr int failed = 1;      // any error not named below
constexpr int bad_input = 2;   // the scene or the command line, before the run
constexpr int stopped = 3;     // aborted by the launcher or a signal
constexpr int diverged = 4;    // its own divergence guard, or a partner's implausible sample
}  // namespace node_exit_code

// One node that stopped running.
struct NodeExit {
  std::string node;
  bool clean = false;     // finished normally (exit code 0)
  bool crashed = false;   // died on a signal (killed, a crash, the OOM killer): a restart may help
  bool diverged = false;  // exit code node_exit_code::diverged
  // Its host saw the node's end record (node_end_record.h): a remote node's agent reads it
  // where the node ran, before the files come back.
  bool reached_end = false;
};

// The NodeExit of `node` from its exit code (or its signal).
inline NodeExit node_exit(std::string node, int exit_code, bool signalled) {
  return {std::move(node), !signalled && exit_code == node_exit_code::done, signalled,
          !signalled && exit_code == node_exit_code::diverged};
}

class NodeHost {
 public:
  virtual ~NodeHost() = default;
  // The nodes this host runs, in start order.
  virtual std::vector<std::string> nodes() const = 0;
  // Starts every node.
  virtual void start_all() = 0;
  // The nodes that stopped since the last call (never blocks).
  virtual std::vector<NodeExit> poll() = 0;
  virtual bool exited(const std::string& node) const = 0;
  // "exit code 1", "killed by signal 9 (Killed)", "failed", "running".
  virtual std::string describe_exit(const std::string& node) const = 0;
  // Reached over a network: watched for partitions (its silence may be the link's), not hangs.
  virtual bool remote(const std::string& /*node*/) const { return false; }
  // Where a remote node runs, for messages: "on host press2 (10.77.0.2)".
  virtual std::string placement(const std::string& /*node*/) const { return {}; }
  // Whether an exited node can be started again from a checkpoint (docs/faults.md).
  virtual bool can_restart(const std::string& /*node*/) const { return false; }
  // Starts an exited node again, to resume from its checkpoint of `step` once told (the
  // rollback of `generation`). Nodes sharing a process restart with it, together.
  virtual void restart(const std::string& node, std::uint64_t step, std::int32_t generation);
  // Asks every running node to stop (never blocks); stop_all then makes sure.
  virtual void request_stop() = 0;
  // Waits up to `grace_s` for the nodes asked to stop, then ends the rest for good.
  virtual void stop_all(double grace_s) = 0;
  // Housekeeping of a host reached by messages (agent heartbeats): called from every wait.
  virtual void pump() {}
};

}  // namespace mechsim::cosim
