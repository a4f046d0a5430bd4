#include "stall_resend.h"

#include <algorithm>
#include <cstdio>

namespace mechsim::cosim {

void StallResend::keep(bool prediction, const transport::SampleHeader& h, const std::vector<double>& v, std::size_t kept) {
  if (kept == 0) return clear();
  while (sent_.size() > kept) sent_.erase(sent_.begin());
  if (sent_.size() < kept) {
    sent_.push_back({prediction, h, v});
    return;
  }
  // Full: the oldest slot becomes the newest, its storage reused (no allocation per step).
  std::rotate(sent_.begin(), sent_.begin() + 1, sent_.end());
  SentSample& newest = sent_.back();
  newest.prediction = prediction;
  newest.header = h;
  newest.values.assign(v.begin(), v.end());
}

void StallResend::resend_if_stalled(std::uint64_t step, const char* why) {
  if (sent_.empty()) return;
  const auto now = now_();
  if (now - last_step_taken_ < kResendAfterStall || now - last_resend_ < kResendAfterStall) return;
  if (last_resend_ < last_step_taken_)  // once per stall in the log
    std::printf("%s: no step for %.2f s at step %llu: the newest %zu sample(s) sent again\n", why,
                std::chrono::duration<double>(now - last_step_taken_).count(), static_cast<unsigned long long>(step), sent_.size());
  last_resend_ = now;
  for (const SentSample& s : sent_) {
    if (s.prediction) io_.write_prediction(s.header, s.values);
    else io_.write_own(s.header, s.values);
  }
}

}  // namespace mechsim::cosim
