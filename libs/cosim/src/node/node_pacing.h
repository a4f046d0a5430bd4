// Pacing (`mode: realtime`, docs/realtime.md): publication paced to the wall clock from the
// start command's t_start, what happens when a node falls behind (realtime.on_overrun, the
// cannot-keep-up warning), and how the loop waits for its next samples (realtime.wait).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "mechsim/cosim/pacer.h"
#include "mechsim/cosim/scene_plan.h"
#include "node_status.h"

namespace mechsim::cosim {

class NodePacing {
 public:
  // Paced only in real-time mode; `start`: the start command (its start_wall_ns).
  NodePacing(const ScenePlan& plan, const transport::ControlMessage& start);
  bool paced() const { return pacer_.has_value(); }
  // Before publishing step k: waits for its deadline.
  void wait_for_deadline(std::uint64_t k);
  // After publishing step k at time t: its lateness counted; throws NodeFailure (missed
  // deadline) under on_overrun: abort; warns once when the run cannot keep up at all.
  void published(std::uint64_t k, double t, NodeStatus& status);
  // The figures for the status, at heartbeat pace (they walk the histogram).
  void report(NodeStatus& status) const;
  // Waits for the next samples: blocking, or spinning (realtime.wait: spin) with `poll`
  // (takes samples, true once the node can go on). awaited_step: the step whose samples
  // the node waits for (their deadline is when they are due).
  // longest: at most this long (a process group's executor has other members to serve).
  void wait_for_samples(transport::Participant& participant, const NodeStatus& status, std::uint64_t awaited_step,
                        const std::function<bool()>& poll, std::chrono::nanoseconds longest) const;
  // The node's real-time figures and lateness histogram for the launcher's summary.
  void write_figures(const std::string& path) const;

 private:
  bool spin_until_ready(double limit_s, const std::function<bool()>& poll) const;

  const config::Scene& scene_;
  std::optional<Pacer> pacer_;
  bool keep_up_checked_ = false;
};

}  // namespace mechsim::cosim
