// Test helper: one node of the shipped cam press (the follower, which reads cam/state) with
// its endpoints on an in-process domain, and the partner's side written by the test itself.
// No processes, no DDS: in-process domains are private to the test process. Time is a clock
// the test steps (steady_now.h), so a grace of seconds passes without a sleep.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/step_topic.h"
#include "mechsim/transport/backends.h"
#include "node/node_endpoints.h"
#include "node/node_failure.h"
#include "node/rollback_session.h"
#include "node/sample_gate.h"
#include "scene_files.h"

namespace mechsim::cosim::testing {

// The clock the classes under test read; it moves only when a test advances it. It starts
// an hour after the epoch, as a steady clock does after boot (StallResend's "last resend"
// starts at the epoch).
struct TestClock {
  static inline std::chrono::steady_clock::time_point now_ =
      std::chrono::steady_clock::time_point(std::chrono::hours(1));
  static std::chrono::steady_clock::time_point now() { return now_; }
  static void advance(double seconds) {
    now_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  }
};

// An in-process participant whose redundant endpoints are ordinary ones on the twin topic
// (the in-process transport has none of its own: nothing to lose packets on), so that the
// gate's twin readers can be fed.
class ParticipantWithTwins final : public transport::Participant {
 public:
  explicit ParticipantWithTwins(int domain) : p_(transport::create_participant("inproc", domain)) {}
  std::unique_ptr<transport::SampleWriter> create_writer(const std::string& t, const transport::TopicType& y) override {
    return p_->create_writer(t, y);
  }
  std::unique_ptr<transport::SampleReader> create_reader(const std::string& t, const transport::TopicType& y) override {
    return p_->create_reader(t, y);
  }
  std::unique_ptr<transport::SampleWriter> create_redundant_writer(const std::string& t,
                                                                   const transport::TopicType& y) override {
    return p_->create_writer(transport::redundant_topic(t), y);
  }
  std::unique_ptr<transport::SampleReader> create_redundant_reader(const std::string& t,
                                                                   const transport::TopicType& y) override {
    return p_->create_reader(transport::redundant_topic(t), y);
  }
  std::unique_ptr<transport::ControlWriter> create_control_writer() override { return p_->create_control_writer(); }
  std::unique_ptr<transport::ControlReader> create_control_reader() override { return p_->create_control_reader(); }
  std::unique_ptr<transport::StatusWriter> create_status_writer() override { return p_->create_status_writer(); }
  std::unique_ptr<transport::StatusReader> create_status_reader() override { return p_->create_status_reader(); }
  bool wait(std::chrono::nanoseconds timeout) override { return p_->wait(timeout); }
  void wake() override { p_->wake(); }
  std::string vendor() const override { return p_->vendor(); }

 private:
  std::unique_ptr<transport::Participant> p_;
};

struct NodeOptions {
  bool redundant = false;                           // faults.redundant_samples
  std::optional<std::uint64_t> lose_write_of_step;  // RollbackSession's test seam
};

// Every test its own domain, so that no endpoint of another test is ever matched.
inline int fresh_domain() {
  static int next = 200;
  return next++;
}

inline constexpr std::uint64_t kRunId = 4711;

// The follower of cam_press.yaml with its endpoints, stepper, rollback session and gate,
// wired as NodeLoop wires them (node_runner.cpp).
class FollowerNode {
 public:
  explicit FollowerNode(NodeOptions options = {})
      : domain(fresh_domain()),
        participant(domain),
        io(plan, "follower", participant, options.redundant),
        stepper(node, plan.grid(), plan.nodes().size(), io.self()),
        rollback(io, false, options.lose_write_of_step, &TestClock::now),
        gate(plan, node, io, stepper, rollback, kRunId, domain, false, &TestClock::now) {}

  config::Scene scene = config::load_scene(mechsim::testing::shipped_scene("cam_press.yaml"));
  ScenePlan plan = ScenePlan::build(scene);
  PlannedNode& node = plan.node("follower");
  const InboundEdge& edge = node.inputs.at(0);  // cam/state, Gauss-Seidel
  int domain;
  ParticipantWithTwins participant;
  NodeEndpoints io;
  NodeStepper stepper;
  RollbackSession rollback;
  SampleGate gate;
};

// A cam/state sample inside every bound (0 is inside all of CamState's), with `speed`
// (bounded to +-1e4 rad/s, a field the follower reads) set to `speed`.
inline std::vector<double> cam_sample(const FollowerNode& f, double speed) {
  std::vector<double> v(f.edge.type->fields.size(), 0.0);
  v.at(static_cast<std::size_t>(f.edge.type->field_index("speed"))) = speed;
  return v;
}

inline transport::SampleHeader header(std::uint64_t step, std::uint64_t run_id = kRunId) {
  return {run_id, step, 1e-3 * static_cast<double>(step)};
}

// The NodeFailure `f` throws (none: nullopt).
template <class F>
std::optional<NodeFailure> failure_of(F&& f) {
  try {
    f();
  } catch (const NodeFailure& e) {
    return e;
  }
  return std::nullopt;
}

// Success when `f` throws a NodeFailure of `kind` whose message holds every one of `phrases`.
template <class F>
::testing::AssertionResult fails_with(F&& f, transport::NodeError kind,
                                      std::initializer_list<std::string> phrases = {}) {
  const std::optional<NodeFailure> e = failure_of(f);
  if (!e) return ::testing::AssertionFailure() << "no NodeFailure thrown";
  if (e->kind() != kind)
    return ::testing::AssertionFailure() << "NodeFailure of kind " << static_cast<int>(e->kind()) << ", not "
                                         << static_cast<int>(kind) << ": " << e->what();
  const std::string what = e->what();
  for (const std::string& phrase : phrases)
    if (what.find(phrase) == std::string::npos)
      return ::testing::AssertionFailure() << "no '" << phrase << "' in: " << what;
  return ::testing::AssertionSuccess();
}

}  // namespace mechsim::cosim::testing
