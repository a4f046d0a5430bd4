#include "mechsim/cosim/inproc_run.h"

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "mechsim/cosim/node_runner.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/backends.h"

namespace mechsim::cosim {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// In-process domains are private to this process: a counter keeps concurrent runs (tests,
// a bench) apart.
int next_domain() {
  static std::atomic<int> counter{0};
  return 1'000'000 + counter.fetch_add(1);
}

}  // namespace

InprocRunResult run_inproc(const config::Scene& scene, const InprocRunOptions& options) {
  const int domain = next_domain();
  const std::size_t n = scene.participants.size();
  // One plan per node, like one per node process (blocks hold run state).
  std::vector<std::unique_ptr<ScenePlan>> plans;
  for (std::size_t i = 0; i < n; ++i) plans.push_back(std::make_unique<ScenePlan>(ScenePlan::build(scene)));

  auto launcher = transport::create_participant("inproc", domain);
  auto control = launcher->create_control_writer();
  auto status = launcher->create_status_reader();

  struct Slot {
    std::string name;
    std::unique_ptr<transport::Participant> participant;
    std::thread thread;
    std::atomic<int> exit_code{-1};
    std::atomic<bool> finished{false};
    transport::StatusMessage last;
    bool seen = false;
    bool done = false;
    double done_at_s = -1;
    Clock::time_point last_seen{};
  };
  std::vector<std::unique_ptr<Slot>> slots;
  std::atomic<bool> stop{false};
  InprocRunResult result;

  auto take_status = [&] {
    while (auto s = status->take()) {
      if (s->header.run_id != options.run_id) continue;
      for (auto& slot : slots)
        if (slot->name == s->node) {
          slot->last = *s;
          slot->seen = true;
          slot->last_seen = Clock::now();
        }
    }
  };
  auto fail = [&](const std::string& node, const std::string& reason) {
    if (!result.reason.empty()) return;
    result.ok = false;
    result.failed_node = node;
    result.reason = reason;
    for (auto& slot : slots) result.diverged = result.diverged || (slot->name == node && slot->seen && transport::points_to_divergence(slot->last.error));
    for (auto& slot : slots)
      if (slot->name == node && slot->seen) result.failed_step = slot->last.header.step;
  };
  auto check_exits = [&] {
    for (auto& slot : slots)
      if (slot->finished && slot->exit_code != 0) {
        take_status();  // its final status carries the message
        fail(slot->name, "node '" + slot->name + "' " +
                             (slot->exit_code == 1 ? "failed" : "stopped (exit code " + std::to_string(slot->exit_code) + ")") +
                             (slot->last.message.empty() ? "" : ": " + slot->last.message));
      }
  };
  auto stop_all = [&] {
    stop = true;
    for (auto& slot : slots) slot->participant->wake();
  };

  for (std::size_t i = 0; i < n; ++i) {
    auto slot = std::make_unique<Slot>();
    slot->name = scene.participants[i].name;
    slot->participant = transport::create_participant("inproc", domain);
    slots.push_back(std::move(slot));
  }
  for (std::size_t i = 0; i < n; ++i) {
    Slot* slot = slots[i].get();
    ScenePlan* plan = plans[i].get();
    slot->thread = std::thread([slot, plan, &options, &stop] {
      NodeRunOptions o;
      o.run_dir = options.run_dir;
      o.run_id = options.run_id;
      o.stop_requested = &stop;
      int code = 1;
      try {
        code = run_node(*plan, slot->name, *slot->participant, o);
      } catch (const std::exception&) {
        code = 1;  // run_node reports its own errors; this is only a last resort
      }
      slot->exit_code = code;
      slot->finished = true;
    });
  }

  // 1. Every node ready.
  const auto launched = Clock::now();
  for (;;) {
    take_status();
    check_exits();
    if (!result.reason.empty()) break;
    bool all_ready = true;
    for (auto& slot : slots) all_ready = all_ready && slot->seen && slot->last.state == transport::NodeState::ready;
    if (all_ready) break;
    if (seconds_since(launched) > options.ready_timeout_s) {
      fail("", "nodes not ready after " + std::to_string(options.ready_timeout_s) + " s");
      break;
    }
    launcher->wait(std::chrono::milliseconds(5));
  }

  // 2. Start, then watch until every node is done or one fails.
  transport::ControlMessage start{options.run_id, transport::ControlCommand::start, scene.time.end, scene.time.step,
                                  transport::RunMode::lockstep, scene.rtf, 0, 0, 0, {}};
  const auto started = Clock::now();
  if (result.reason.empty()) {
    control->write(start);
    for (auto& slot : slots) slot->last_seen = started;
    auto last_progress = Clock::now();
    for (;;) {
      take_status();
      for (auto& slot : slots)
        if (slot->seen && slot->last.state == transport::NodeState::done && slot->done_at_s < 0)
          slot->done_at_s = seconds_since(started);
      check_exits();
      if (!result.reason.empty()) break;
      bool all = true;
      for (auto& slot : slots) all = all && slot->finished;
      if (all) {
        result.ok = true;
        break;
      }
      // A hung node (no status for the scene's hang timeout): its thread cannot be killed,
      // but the others stop and the run is reported failed.
      for (auto& slot : slots)
        if (!slot->finished && std::chrono::duration<double>(Clock::now() - slot->last_seen).count() > scene.hang_timeout)
          fail(slot->name, "node '" + slot->name + "' hung: no status for " + std::to_string(scene.hang_timeout) + " s");
      if (!result.reason.empty()) break;
      if (options.progress && seconds_since(last_progress) > 0.2) {
        std::uint64_t step = UINT64_MAX;
        for (auto& slot : slots) step = std::min<std::uint64_t>(step, slot->seen ? slot->last.header.step : 0);
        options.progress(step);
        last_progress = Clock::now();
      }
      launcher->wait(std::chrono::milliseconds(20));
    }
  }
  result.wall_time_s = seconds_since(started);
  if (!result.ok) {
    transport::ControlMessage abort = start;
    abort.command = transport::ControlCommand::abort;
    control->write(abort);
    stop_all();
  }
  for (auto& slot : slots) slot->thread.join();
  take_status();
  double done_max = 0;
  bool all_done = true;
  for (auto& slot : slots) {
    all_done = all_done && slot->done_at_s >= 0;
    done_max = std::max(done_max, slot->done_at_s);
  }
  if (result.ok && all_done) result.wall_time_s = done_max;
  for (auto& slot : slots) result.nodes.push_back({slot->name, slot->exit_code.load(), slot->last});
  return result;
}

}  // namespace mechsim::cosim
