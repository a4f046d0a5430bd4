#include <utility>

#include "step_observers.h"

namespace mechsim::cosim {

void StatusObserver::step_completed(const CompletedStep& s) {
  status_.at_step(s.step, s.t);
  status_.copy_stats(s.stepper.solver_stats());  // statistics on every heartbeat
  if (std::exchange(announce_, false)) status_.send();
}

}  // namespace mechsim::cosim
