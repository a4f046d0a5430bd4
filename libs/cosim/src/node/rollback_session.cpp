#include "rollback_session.h"

#include <cstdio>
#include <utility>

namespace mechsim::cosim {

bool RollbackSession::within_after_resume(double seconds) const {
  return resumed_at_ && Clock::now() - *resumed_at_ < std::chrono::duration<double>(seconds);
}

void RollbackSession::keep(bool prediction, const transport::SampleHeader& h, const std::vector<double>& v) {
  if (!within_after_resume(kForeignWriterGrace)) return;  // no clock read in a run without rollback
  if (sent_.size() == kSentKept) sent_.erase(sent_.begin());
  sent_.push_back({prediction, h, v});
}

void RollbackSession::write_own(const transport::SampleHeader& h, const std::vector<double>& v) {
  io_.write_own(h, v);
  keep(false, h, v);
}

void RollbackSession::write_prediction(const transport::SampleHeader& h, const std::vector<double>& v) {
  if (!std::exchange(lose_next_prediction_, false)) io_.write_prediction(h, v);
  keep(true, h, v);
}

void RollbackSession::go_on(const transport::SampleHeader& h, const std::vector<double>& v) {
  resumed_at_ = Clock::now();
  sent_.clear();
  last_step_taken_ = Clock::now();
  lose_next_prediction_ = lose_first_writes_ && io_.has_cut();
  if (!lose_first_writes_) io_.write_own(h, v);
  keep(false, h, v);
}

void RollbackSession::resend_if_stalled(std::uint64_t step) {
  if (sent_.empty() || !within_after_resume(kForeignWriterGrace)) return;
  const auto now = Clock::now();
  if (now - last_step_taken_ < kResendAfterStall || now - last_resend_ < kResendAfterStall) return;
  if (last_resend_ < last_step_taken_)  // once per stall in the log
    std::printf("rollback: no step for %.2f s at step %llu: %zu sample(s) sent since the rollback sent again\n",
                std::chrono::duration<double>(now - last_step_taken_).count(), static_cast<unsigned long long>(step), sent_.size());
  last_resend_ = now;
  for (const SentSample& s : sent_) {
    if (s.prediction) io_.write_prediction(s.header, s.values);
    else io_.write_own(s.header, s.values);
  }
}

}  // namespace mechsim::cosim
