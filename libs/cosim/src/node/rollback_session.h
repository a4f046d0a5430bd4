// What a node does differently after a rollback's resume (docs/faults.md, 'Restart with
// rollback'): the leniency windows counted from the resume, and the resend window.
//
// A restarted node's writers and readers are new to its partners, and DDS discovery
// completes on each side on its own: a sample written before the other side matched a
// writer never arrives (VOLATILE), and lock step would wait for it for good (seen in CI).
// So for kForeignWriterGrace after the resume a node keeps what it wrote since the
// rollback and writes it again whenever it has waited kResendAfterStall without taking a
// step; receivers take the copies as repeats (SampleGate). A lost sample stalls its
// receiver, and in a loop of partners that stall reaches the sender.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "node_endpoints.h"

namespace mechsim::cosim {

class RollbackSession {
 public:
  // A second writer: hold (use no sample) while it lasts; a writer of a process that died
  // lingers until its DDS lease runs out (2 s; a domain is reused by later runs), so only a
  // second writer that stays longer than this is foreign. Also the resend window, and no
  // partition while it lasts.
  static constexpr double kForeignWriterGrace = 4.0;  // s, above the 2 s lease of config/dds/
  // Longer, so that a copy sent at the edge is still taken: a step from the rollback's step
  // up to the newest one seen is a repeat, and a restarted partner's dead writer may linger
  // beside its new one (it took more than 4 s under load once).
  static constexpr double kLingeringAfterResume = 10.0;  // s

  // lose_first_writes: the test seam of NodeRunOptions::lose_first_writes_after_resume.
  RollbackSession(NodeEndpoints& io, bool lose_first_writes) : io_(io), lose_first_writes_(lose_first_writes) {}

  // Within `seconds` of the last resume (false when never rolled back).
  bool within_after_resume(double seconds) const;
  // The step of the checkpoint last restored (none: never rolled back).
  const std::optional<std::uint64_t>& rollback_step() const { return rollback_step_; }
  void restored(std::uint64_t step) { rollback_step_ = step; }

  // The node's writes, kept for sending again while the window lasts.
  void write_own(const transport::SampleHeader& h, const std::vector<double>& v);
  void write_prediction(const transport::SampleHeader& h, const std::vector<double>& v);
  void step_taken() { last_step_taken_ = Clock::now(); }
  // The run goes on from the restored step: its sample once more (the partners rolled back
  // as well and need it), and the window opens.
  void go_on(const transport::SampleHeader& h, const std::vector<double>& v);
  // Sends again what was written since the rollback when no step was taken for a while.
  void resend_if_stalled(std::uint64_t step);

 private:
  using Clock = std::chrono::steady_clock;
  struct SentSample {
    bool prediction;  // the cut topic, else the node's own topic
    transport::SampleHeader header;
    std::vector<double> values;
  };
  static constexpr std::size_t kSentKept = 64;  // the newest; partners in lock step are a step or two apart
  static constexpr auto kResendAfterStall = std::chrono::milliseconds(100);
  void keep(bool prediction, const transport::SampleHeader& h, const std::vector<double>& v);

  NodeEndpoints& io_;
  const bool lose_first_writes_;
  bool lose_next_prediction_ = false;
  std::optional<Clock::time_point> resumed_at_;
  std::optional<std::uint64_t> rollback_step_;
  std::vector<SentSample> sent_;
  Clock::time_point last_step_taken_ = Clock::now(), last_resend_{};
};

}  // namespace mechsim::cosim
