// The node's waits for the launcher: ready (matched with every partner), then the start
// command; after a rollback, the resume. Heartbeats go on meanwhile; no sample is taken.
// Both waits are polled, never block: a node alone naps between polls (nap()), the
// members of a process group are polled in turn by their one executor thread.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>

#include "control_inbox.h"
#include "node_endpoints.h"
#include "node_status.h"

namespace mechsim::cosim {

// Reports ready once the node is matched with every partner, then takes the launcher's
// `awaited` command (start; resume for a restarted node) of `generation`.
class StartWait {
 public:
  StartWait(NodeEndpoints& io, ControlInbox& control, NodeStatus& status, transport::ControlCommand awaited,
            std::int32_t generation, double timeout_s);
  enum class Outcome { waiting, started, ended };
  // One look at the endpoints and the commands. ended: the run was stopped or aborted
  // meanwhile. Throws when no such command comes within timeout_s.
  Outcome poll();
  const transport::ControlMessage& start() const { return *start_; }
  // How long to sleep before the next poll.
  std::chrono::nanoseconds nap() const;

 private:
  NodeEndpoints& io_;
  ControlInbox& control_;
  NodeStatus& status_;
  const transport::ControlCommand awaited_;
  const std::int32_t generation_;
  const std::chrono::steady_clock::time_point deadline_;
  bool ready_ = false;
  std::optional<transport::ControlMessage> start_;
};

// After a rollback: takes the resume of `generation`.
class ResumeWait {
 public:
  ResumeWait(ControlInbox& control, NodeStatus& status, std::int32_t generation)
      : control_(control), status_(status), generation_(generation) {}
  enum class Outcome { waiting, resumed, ended };
  // Throws on a second rollback before the run resumed.
  Outcome poll();
  std::chrono::nanoseconds nap() const;

 private:
  ControlInbox& control_;
  NodeStatus& status_;
  const std::int32_t generation_;
};

}  // namespace mechsim::cosim
