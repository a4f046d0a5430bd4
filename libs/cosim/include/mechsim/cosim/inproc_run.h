// One run of a scene with every node stepped by one executor thread of this process, over the in-process
// transport ("inproc" backend): the same node code (run_node) as the node processes,
// driven the way `mechsim launch` drives processes: wait until every node is ready, send
// start on mechsim/control, watch mechsim/status until every node is done, abort all on
// the first failure. Results do not depend on timing, so a run gives the same numbers as
// over DDS (tests/integration/dds_vendor_test.cpp, VendorRuns.*InProcess: bit-identical node logs).
//
// Each node gets its own ScenePlan (its own blocks), built here on the calling thread, as
// each node process builds its own; run_node keeps no global state.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/transport/messages.h"

namespace mechsim::cosim {

struct InprocRunOptions {
  std::string run_dir;            // <node>.outputs.bin and .events.jsonl go here (must exist)
  std::uint64_t run_id = 1;
  double ready_timeout_s = 30.0;  // from thread start to all nodes ready
  // Called now and then while the nodes step, with the lowest step any node published.
  std::function<void(std::uint64_t step)> progress;
};

struct InprocNodeResult {
  std::string name;
  int exit_code = -1;                 // run_node's: 0 done, 1 failed, 3 aborted
  transport::StatusMessage last;      // its last status (solver statistics, message)
};

struct InprocRunResult {
  bool ok = false;
  std::string failed_node;
  std::string reason;                 // "node 'slide' failed: diverged at step ..."
  bool diverged = false;              // the failure was a node's divergence guard
  std::uint64_t failed_step = 0;
  double wall_time_s = 0.0;           // start command -> every node done
  std::vector<InprocNodeResult> nodes;  // in scene order
};

// Throws config::ConfigError for a scene the plan refuses.
InprocRunResult run_inproc(const config::Scene& scene, const InprocRunOptions& options);

}  // namespace mechsim::cosim
