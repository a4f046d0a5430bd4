// Operating-system real-time settings of a node process: SCHED_FIFO priority, locked and
// pre-faulted memory, CPU affinity (a scene's `realtime: {priority, lock_memory, cpus}`,
// docs/realtime.md). The launcher checks the rights before it starts any process (one clear
// message instead of a node failing), the node process applies the settings before it
// creates its DDS participant so that the vendor's threads inherit the policy.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/scene.h"

namespace mechsim::cosim {

// What this process may do, read from the kernel (credentials, capabilities, rlimits).
struct ProcessRights {
  bool root = false;
  bool cap_sys_nice = false;      // SCHED_FIFO at any priority, affinity
  bool cap_ipc_lock = false;      // mlockall without a limit
  long rtprio_limit = 0;          // RLIMIT_RTPRIO (soft)
  bool memlock_unlimited = false; // RLIMIT_MEMLOCK = infinity
  std::vector<int> allowed_cpus;  // sched_getaffinity of this process
};
ProcessRights current_process_rights();

// Empty when a process with `rights` may apply `spec`; otherwise one sentence naming the
// scene key, what the setting needs and what the process has.
std::string realtime_refusal(const config::ProcessRealtimeSpec& spec, const ProcessRights& rights);

// What was applied, for the node's log and the run summary.
struct AppliedRealtime {
  std::string policy = "SCHED_OTHER";
  int priority = 0;
  bool memory_locked = false;
  std::vector<int> cpus;  // empty: not pinned
  std::string describe() const;  // "SCHED_FIFO 50, memory locked, cpus [1]"
  std::string to_json() const;
  void write_json(const std::string& path) const;  // <run>/<node>.process.json, for the summary
};

// Applies `spec` to the calling process (the policy to the calling thread, which threads
// created afterwards inherit). Throws std::runtime_error with the refusal or the failing
// call and its errno; never ignores a setting silently.
AppliedRealtime apply_process_realtime(const config::ProcessRealtimeSpec& spec);

}  // namespace mechsim::cosim
