#include "step_observers.h"

namespace mechsim::cosim {

void CheckpointObserver::step_completed(const CompletedStep& s) {
  if (s.initial || s.finished || s.step % static_cast<std::uint64_t>(every_) != 0) return;
  write_checkpoint(run_dir_, node_, take_(), keep_, pause_step_ == s.step ? pause_s_ : 0.0);
}

}  // namespace mechsim::cosim
