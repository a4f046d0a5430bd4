// The partition watch (docs/faults.md, 'Cut links'): waiting longer than
// faults.partition_grace for a partner's sample ends the run, naming the partner and its
// host; a shorter wait is just a stall.
#pragma once

#include <chrono>
#include <cstdint>

#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/scene_plan.h"
#include "steady_now.h"

namespace mechsim::cosim {

class PartitionWatch {
 public:
  // now: the clock of the wait (steady_now.h; a unit test steps its own).
  PartitionWatch(const ScenePlan& plan, const PlannedNode& node, double partition_grace, SteadyNow now = steady_now);
  // The wait so far does not count (a hold for a second writer is no partition).
  void excuse() { waiting_since_ = now_(); }
  // Called while the node waits: throws NodeFailure (partner unreachable) once the node has
  // waited longer than the grace at one step. lenient: right after a rollback's resume.
  void check(NodeStepper& stepper, bool initialised, bool lenient);

 private:
  const ScenePlan& plan_;
  const PlannedNode& node_;
  double grace_;
  SteadyNow now_;
  std::chrono::steady_clock::time_point waiting_since_;
  std::uint64_t waiting_step_ = UINT64_MAX;
};

}  // namespace mechsim::cosim
