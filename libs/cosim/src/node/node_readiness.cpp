#include "node_readiness.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

namespace mechsim::cosim {

namespace {

bool stopped(const std::atomic<bool>* stop_requested) { return stop_requested && stop_requested->load(); }

// Not the waitset: a partner that started first may already have sent its step 0, which
// these waits do not take, so the waitset would return at once and this thread would spin;
// under SCHED_FIFO on a pinned CPU that spin starves the node's own DDS receive thread,
// which would deliver the command (a livelock, seen here). A 2 ms sleep is early enough:
// step 0 is due 50 ms after the start command. Until this node is matched, 10 ms: discovery
// takes tens of milliseconds to seconds, and with 32 nodes polling every 1 ms their
// wake-ups competed with discovery for the cores and made the start cost grow with the
// square of the participants (docs/performance.md).
constexpr std::chrono::nanoseconds kNapMatching{10'000'000}, kNapReady{2'000'000}, kNapResume{1'000'000};
void nap(const NodeStatus& status, std::chrono::nanoseconds longest) {
  std::this_thread::sleep_for(std::min(status.until_next(), longest));
}

}  // namespace

std::optional<transport::ControlMessage> await_start(NodeEndpoints& io, ControlInbox& control, NodeStatus& status,
                                                     transport::ControlCommand awaited, std::int32_t generation,
                                                     double timeout_s, const std::atomic<bool>* stop_requested) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  bool ready = false;
  std::optional<transport::ControlMessage> start;
  while (!start) {
    if (stopped(stop_requested)) return std::nullopt;
    if (Clock::now() > deadline) throw std::runtime_error("no start command within the start timeout");
    // For the launcher: it starts the run once every reader on the domain, a recorder of
    // the user's included, is matched with this writer (docs/recording.md).
    status.set_readers_matched(io.readers_matched_including_tools());
    if (!ready && io.matched()) {
      ready = true;
      status.set_state(transport::NodeState::ready);
    }
    while (auto c = control.next()) {
      if (ControlInbox::ends_the_run(*c)) return std::nullopt;
      if (c->command != awaited || c->generation != generation) continue;  // e.g. the rollback a resumed node is part of
      if (!ready) throw std::runtime_error("start command before this node was matched with its partners");
      start = *c;
    }
    status.tick();
    if (!start) nap(status, ready ? kNapReady : kNapMatching);
  }
  return start;
}

bool await_resume(ControlInbox& control, NodeStatus& status, std::int32_t generation, const std::atomic<bool>* stop_requested) {
  for (;;) {
    if (stopped(stop_requested)) return false;
    while (auto c = control.next()) {
      if (ControlInbox::ends_the_run(*c)) return false;
      if (c->command == transport::ControlCommand::resume && c->generation == generation) return true;
      if (c->command == transport::ControlCommand::rollback && c->generation > generation)
        throw std::runtime_error("a second rollback (generation " + std::to_string(c->generation) + ") before the run resumed");
    }
    status.tick();
    nap(status, kNapResume);
  }
}

}  // namespace mechsim::cosim
