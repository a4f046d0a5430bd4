// Observers see every completed step of the node, after it was published, in the order
// they were added: the output log, the events file, the status (statistics) and the
// checkpoints. A new kind of output is a new observer, not an edit of the node loop.
#pragma once

#include <cstdint>

#include "mechsim/cosim/checkpoint.h"
#include "mechsim/cosim/node_stepper.h"

namespace mechsim::cosim {

struct CompletedStep {
  std::uint64_t step = 0;
  double t = 0;
  NodeStepper& stepper;
  bool initial = false;   // step 0: the initial outputs, no step taken
  bool finished = false;  // the last step of the run
};

class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void step_completed(const CompletedStep& s) = 0;
  // Its part of a checkpoint of the current step, and back to a checkpoint's step (a
  // rollback): what it wrote after that step is cut off, so the run folder ends as an
  // undisturbed run's.
  virtual void add_to(NodeCheckpoint&) {}
  virtual void restore(const NodeCheckpoint&) {}
  // The run is complete.
  virtual void finish() {}
};

}  // namespace mechsim::cosim
