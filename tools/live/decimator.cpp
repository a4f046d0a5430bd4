#include "decimator.h"

#include <cmath>

namespace mechsim::live {

namespace {
void assign(TimedSample& s, std::uint64_t t_ns, std::span<const std::byte> cdr) {
  s.t_ns = t_ns;
  s.cdr.assign(cdr.begin(), cdr.end());  // reuses the buffer's capacity
  s.valid = true;
}
}  // namespace

void Decimator::offer(std::uint64_t t_ns, std::span<const std::byte> cdr) {
  ++offered_;
  // A time before the last sent one: a new run on the domain, a rollback, a bag looping.
  if (latest_.valid && t_ns < latest_.t_ns) next_due_ns_ = t_ns;
  assign(latest_, t_ns, cdr);
  if (!pending_.valid && t_ns >= next_due_ns_) assign(pending_, t_ns, cdr);
}

bool Decimator::due(Clock::time_point now, TimedSample& out) {
  if (latest_.valid) {
    if (!marked_) {
      mark_t_ns_ = latest_.t_ns;
      mark_wall_ = now;
      marked_ = true;
    } else if (const double wall_s = std::chrono::duration<double>(now - mark_wall_).count(); wall_s >= 0.25) {
      // Simulated seconds per wall second, over the last quarter second or more.
      const double pace = latest_.t_ns >= mark_t_ns_ ? static_cast<double>(latest_.t_ns - mark_t_ns_) / wall_s : 0.0;
      stride_ns_ = static_cast<std::uint64_t>(std::llround(pace / rate_hz_));
      mark_t_ns_ = latest_.t_ns;
      mark_wall_ = now;
    }
  }
  if (!pending_.valid) return false;
  out.t_ns = pending_.t_ns;
  out.cdr.swap(pending_.cdr);
  out.valid = true;
  pending_.valid = false;
  next_due_ns_ = out.t_ns + stride_ns_;
  // The latest sample may already be due (the run is faster than the measured pace).
  if (latest_.valid && latest_.t_ns >= next_due_ns_ && latest_.t_ns > out.t_ns) assign(pending_, latest_.t_ns, latest_.cdr);
  return true;
}

}  // namespace mechsim::live
