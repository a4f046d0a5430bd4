#include "step_observers.h"

namespace mechsim::cosim {

void OutputLogObserver::step_completed(const CompletedStep& s) {
  if (!s.initial)
    if (const auto* row = s.stepper.event_row()) log_->append(s.stepper.grid().time(s.step - 1), *row);
  if (!s.stepper.grid().is_event(s.step)) log_->append(s.t, s.stepper.outputs());
}

void OutputLogObserver::add_to(NodeCheckpoint& c) {
  log_->flush();
  c.output_rows = log_->rows();
}

}  // namespace mechsim::cosim
