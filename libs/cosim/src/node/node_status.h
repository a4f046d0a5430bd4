// The node's status on mechsim/status: sent on every change of state and as a heartbeat
// while the node waits or computes. The launcher acts on its typed fields (state, the
// rollback it holds, warning, error); the message words the same for people.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "mechsim/cosim/pacer.h"
#include "mechsim/solve/solver_options.h"
#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

class NodeStatus {
 public:
  NodeStatus(transport::Participant& participant, std::string node, std::uint64_t run_id, std::int32_t generation,
             double period_s);
  // Seconds since the node started.
  double elapsed() const;
  void set_state(transport::NodeState s);
  // Sends when the period has passed since the last one; send() at once.
  void tick();
  void send();
  std::chrono::nanoseconds until_next() const;

  void at_step(std::uint64_t step, double t);
  void set_readers_matched(int readers);
  // Back at the checkpoint of `step` in `generation`, waiting for resume (the launcher
  // resumes once every node says so), and running again.
  void rolled_back(std::uint64_t step, std::int32_t generation);
  void resumed();
  void warn(transport::NodeWarning warning, const std::string& text);
  void failed(transport::NodeError error, const std::string& text);
  void copy_stats(const solve::SolverStats* stats);
  void copy_realtime(const RealtimeFigures& figures);

 private:
  std::unique_ptr<transport::StatusWriter> writer_;
  std::chrono::nanoseconds period_;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point next_{};
  transport::StatusMessage status_;
};

}  // namespace mechsim::cosim
