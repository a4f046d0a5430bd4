#include "rollback_session.h"

#include <cstdio>
#include <utility>

namespace mechsim::cosim {

bool RollbackSession::within_after_resume(double seconds) const {
  return resumed_at_ && now_() - *resumed_at_ < std::chrono::duration<double>(seconds);
}

void RollbackSession::keep(bool prediction, const transport::SampleHeader& h, const std::vector<double>& v) {
  resend_.keep(prediction, h, v, within_after_resume(kForeignWriterGrace) ? kSentKept : StallResend::kKeptSteady);
}

void RollbackSession::write_own(const transport::SampleHeader& h, const std::vector<double>& v) {
  if (lose_write_of_step_ == h.step) lose_write_of_step_.reset();  // the test seam: this write is lost
  else io_.write_own(h, v);
  keep(false, h, v);
}

void RollbackSession::write_prediction(const transport::SampleHeader& h, const std::vector<double>& v) {
  if (!std::exchange(lose_next_prediction_, false)) io_.write_prediction(h, v);
  keep(true, h, v);
}

void RollbackSession::go_on(const transport::SampleHeader& h, const std::vector<double>& v) {
  resumed_at_ = now_();
  resend_.clear();
  resend_.step_taken();
  lose_next_prediction_ = lose_first_writes_ && io_.has_cut();
  if (!lose_first_writes_) io_.write_own(h, v);
  keep(false, h, v);
}

void RollbackSession::resend_if_stalled(std::uint64_t step) {
  resend_.resend_if_stalled(step, within_after_resume(kForeignWriterGrace) ? "rollback" : "lock step");
}

}  // namespace mechsim::cosim
