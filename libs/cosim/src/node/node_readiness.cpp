#include "node_readiness.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace mechsim::cosim {

namespace {

// Not the waitset: a partner that started first may already have sent its step 0, which
// these waits do not take, so the waitset would return at once and this thread would spin;
// under SCHED_FIFO on a pinned CPU that spin starves the node's own DDS receive thread,
// which would deliver the command (a livelock, seen here). A 2 ms nap is early enough:
// step 0 is due 50 ms after the start command. Until this node is matched, 10 ms: discovery
// takes tens of milliseconds to seconds, and with 32 nodes polling every 1 ms their
// wake-ups competed with discovery for the cores and made the start cost grow with the
// square of the participants (docs/performance.md).
constexpr std::chrono::nanoseconds kNapMatching{10'000'000}, kNapReady{2'000'000}, kNapResume{1'000'000};

std::chrono::steady_clock::time_point deadline_after(double seconds) {
  using Clock = std::chrono::steady_clock;
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

StartWait::StartWait(NodeEndpoints& io, ControlInbox& control, NodeStatus& status, transport::ControlCommand awaited,
                     std::int32_t generation, double timeout_s)
    : io_(io), control_(control), status_(status), awaited_(awaited), generation_(generation), deadline_(deadline_after(timeout_s)) {}

StartWait::Outcome StartWait::poll() {
  if (start_) return Outcome::started;
  if (std::chrono::steady_clock::now() > deadline_) throw std::runtime_error("no start command within the start timeout");
  // For the launcher: it starts the run once every reader on the domain, a recorder of
  // the user's included, is matched with this writer (docs/recording.md).
  status_.set_readers_matched(io_.readers_matched_including_tools());
  if (!ready_ && io_.matched()) {
    ready_ = true;
    status_.set_state(transport::NodeState::ready);
  }
  while (auto c = control_.next()) {
    if (ControlInbox::ends_the_run(*c)) return Outcome::ended;
    if (c->command != awaited_ || c->generation != generation_) continue;  // e.g. the rollback a resumed node is part of
    if (!ready_) throw std::runtime_error("start command before this node was matched with its partners");
    start_ = *c;
  }
  status_.tick();
  return start_ ? Outcome::started : Outcome::waiting;
}

std::chrono::nanoseconds StartWait::nap() const { return std::min(status_.until_next(), ready_ ? kNapReady : kNapMatching); }

ResumeWait::Outcome ResumeWait::poll() {
  while (auto c = control_.next()) {
    if (ControlInbox::ends_the_run(*c)) return Outcome::ended;
    if (c->command == transport::ControlCommand::resume && c->generation == generation_) return Outcome::resumed;
    if (c->command == transport::ControlCommand::rollback && c->generation > generation_)
      throw std::runtime_error("a second rollback (generation " + std::to_string(c->generation) + ") before the run resumed");
  }
  status_.tick();
  return Outcome::waiting;
}

std::chrono::nanoseconds ResumeWait::nap() const { return std::min(status_.until_next(), kNapResume); }

}  // namespace mechsim::cosim
