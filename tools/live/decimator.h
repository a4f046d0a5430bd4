// Which samples of one channel a live viewer gets (docs/live.md, 'Decimation'). A run can
// publish tens of thousands of samples a second; a viewer takes tens. The server sends a
// channel at most once per tick (the tick period is 1 / rate), so never more than `rate`
// messages a second, and picks them evenly in simulation time: the sample sent is the
// first one at or after the last sent time plus a stride, where the stride is the
// simulated time that passes in one tick at the pace measured over the last quarter
// second. The latest sample is kept too, for a viewer that subscribes late.
//
// offer() is called by the thread that reads the samples, due() by the server's tick:
// the caller serialises them (LiveServer holds one mutex for all its channels).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mechsim::live {

struct TimedSample {
  std::uint64_t t_ns = 0;  // simulation time
  std::vector<std::byte> cdr;
  bool valid = false;
};

class Decimator {
 public:
  using Clock = std::chrono::steady_clock;
  explicit Decimator(double rate_hz) : rate_hz_(rate_hz) {}

  void offer(std::uint64_t t_ns, std::span<const std::byte> cdr);
  // The sample to send at this tick, if one is due (copied into `out`, whose buffer is
  // reused); false when nothing is.
  bool due(Clock::time_point now, TimedSample& out);
  const TimedSample& latest() const { return latest_; }
  // Simulated ns between two sent samples, as last measured (0 until measured).
  std::uint64_t stride_ns() const { return stride_ns_; }
  std::uint64_t offered() const { return offered_; }

 private:
  double rate_hz_;
  TimedSample latest_, pending_;
  std::uint64_t next_due_ns_ = 0;
  std::uint64_t stride_ns_ = 0;
  std::uint64_t offered_ = 0;
  // The pace measurement: the latest simulated time at the mark, and the mark's wall time.
  std::uint64_t mark_t_ns_ = 0;
  Clock::time_point mark_wall_{};
  bool marked_ = false;
};

}  // namespace mechsim::live
