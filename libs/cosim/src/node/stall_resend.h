// Lock step waits for every partner's sample of a step, so a sample that never arrives
// stalls the run for good: the reliable stream may skip one (seen under 5 % loss between a
// Fast DDS writer and a Cyclone DDS reader at the start of a run, its redundant copy lost
// too), and a restarted node's first writes go out before its partners matched its new
// writers (docs/faults.md). So a node keeps its newest writes and writes them again
// whenever it has waited kResendAfterStall without taking a step; receivers drop the copies
// as repeats (SampleGate). A lost sample stalls its receiver, and in a loop of partners
// that stall reaches the sender, whose copies then repair it.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "node_endpoints.h"
#include "steady_now.h"

namespace mechsim::cosim {

class StallResend {
 public:
  // Partners in lock step are a step or two apart: the newest few writes cover them.
  static constexpr std::size_t kKeptSteady = 4;
  static constexpr auto kResendAfterStall = std::chrono::milliseconds(100);

  // now: the clock (steady_now.h; a unit test steps its own).
  explicit StallResend(NodeEndpoints& io, SteadyNow now = steady_now) : io_(io), now_(now), last_step_taken_(now()) {}

  // A write of the node (prediction: the cut topic, else its own topic), kept for sending
  // again; at most `kept` of the newest are kept.
  void keep(bool prediction, const transport::SampleHeader& h, const std::vector<double>& v, std::size_t kept);
  // Forgets what was kept (a rollback: the run goes on from an earlier step).
  void clear() { sent_.clear(); }
  void step_taken() { last_step_taken_ = now_(); }
  // Writes the kept samples again when no step was taken for kResendAfterStall (then again
  // every kResendAfterStall); `why` goes into the log line, printed once per stall.
  void resend_if_stalled(std::uint64_t step, const char* why);

 private:
  using Clock = std::chrono::steady_clock;
  struct SentSample {
    bool prediction;
    transport::SampleHeader header;
    std::vector<double> values;
  };
  NodeEndpoints& io_;
  SteadyNow now_;
  std::vector<SentSample> sent_;
  Clock::time_point last_step_taken_, last_resend_{};
};

}  // namespace mechsim::cosim
