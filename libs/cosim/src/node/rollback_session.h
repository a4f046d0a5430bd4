// What a node does differently after a rollback's resume (docs/faults.md, 'Restart with
// rollback'): the leniency windows counted from the resume, and a wider resend.
//
// A restarted node's writers and readers are new to its partners, and DDS discovery
// completes on each side on its own: a sample written before the other side matched a
// writer never arrives (VOLATILE), and lock step would wait for it for good (seen in CI).
// Every node writes its newest samples again when it stalls (StallResend); for
// kForeignWriterGrace after the resume it keeps everything it wrote since the rollback for
// that (up to kSentKept), and receivers take the copies as repeats (SampleGate).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "node_endpoints.h"
#include "stall_resend.h"

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

  // lose_first_writes, lose_write_of_step: the test seams of NodeRunOptions; now: the
  // clock of the windows and of the resend (steady_now.h; a unit test steps its own).
  RollbackSession(NodeEndpoints& io, bool lose_first_writes, std::optional<std::uint64_t> lose_write_of_step = std::nullopt,
                  SteadyNow now = steady_now)
      : io_(io), lose_first_writes_(lose_first_writes), lose_write_of_step_(lose_write_of_step), now_(now), resend_(io, now) {}

  // Within `seconds` of the last resume (false when never rolled back).
  bool within_after_resume(double seconds) const;
  // The step of the checkpoint last restored (none: never rolled back).
  const std::optional<std::uint64_t>& rollback_step() const { return rollback_step_; }
  void restored(std::uint64_t step) { rollback_step_ = step; }

  // The node's writes, kept for sending again when it stalls (StallResend).
  void write_own(const transport::SampleHeader& h, const std::vector<double>& v);
  void write_prediction(const transport::SampleHeader& h, const std::vector<double>& v);
  void step_taken() { resend_.step_taken(); }
  // The run goes on from the restored step: its sample once more (the partners rolled back
  // as well and need it), and the window opens.
  void go_on(const transport::SampleHeader& h, const std::vector<double>& v);
  // Sends the newest writes again (after a resume: what was written since the rollback)
  // when no step was taken for a while.
  void resend_if_stalled(std::uint64_t step);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::size_t kSentKept = 64;  // after a resume: since the rollback, the newest
  void keep(bool prediction, const transport::SampleHeader& h, const std::vector<double>& v);

  NodeEndpoints& io_;
  const bool lose_first_writes_;
  std::optional<std::uint64_t> lose_write_of_step_;
  SteadyNow now_;
  bool lose_next_prediction_ = false;
  std::optional<Clock::time_point> resumed_at_;
  std::optional<std::uint64_t> rollback_step_;
  StallResend resend_;
};

}  // namespace mechsim::cosim
