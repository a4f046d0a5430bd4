// The observers of a node's steps (step_observer.h), one output each.
#pragma once

#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "node_status.h"
#include "step_observer.h"

namespace mechsim::cosim {

// <node>.outputs.bin: a row per step; an event instant's row when the next step starts
// (NodeStepper::event_row).
class OutputLogObserver final : public StepObserver {
 public:
  explicit OutputLogObserver(std::unique_ptr<OutputLogWriter> log) : log_(std::move(log)) {}
  void step_completed(const CompletedStep& s) override;
  void add_to(NodeCheckpoint& c) override;
  void restore(const NodeCheckpoint& c) override { log_->truncate_rows(c.output_rows); }
  void finish() override { log_->close(); }

 private:
  std::unique_ptr<OutputLogWriter> log_;
};

// Events the block reports (lift-off, landing, ...): a line in the node's log and, with a
// run folder, JSON lines in <node>.events.jsonl for the launcher's summary.
class EventsObserver final : public StepObserver {
 public:
  // path "": no file. resumed: the file exists and is continued (cut at restore()).
  EventsObserver(PlannedNode& node, std::string path, bool resumed);
  ~EventsObserver() override;
  void step_completed(const CompletedStep& s) override;
  void add_to(NodeCheckpoint& c) override;
  void restore(const NodeCheckpoint& c) override;

 private:
  PlannedNode& node_;
  std::string path_;
  std::FILE* file_ = nullptr;
};

// The step and t of the last published step and the integrator statistics on the status;
// after a rollback's resume the first step taken goes to the launcher at once.
class StatusObserver final : public StepObserver {
 public:
  explicit StatusObserver(NodeStatus& status) : status_(status) {}
  void step_completed(const CompletedStep& s) override;
  void announce_next_step() { announce_ = true; }

 private:
  NodeStatus& status_;
  bool announce_ = false;
};

// Restart with rollback (checkpoint.h, docs/faults.md): a checkpoint every `every` steps,
// of the state `take` returns (the stepper, the guard and every observer's part).
class CheckpointObserver final : public StepObserver {
 public:
  // pause_step, pause_s: the test seam of NodeRunOptions::checkpoint_pause_step.
  CheckpointObserver(std::string run_dir, std::string node, long every, int keep, std::function<NodeCheckpoint()> take,
                     std::optional<std::uint64_t> pause_step = std::nullopt, double pause_s = 0.0)
      : run_dir_(std::move(run_dir)), node_(std::move(node)), every_(every), keep_(keep), take_(std::move(take)),
        pause_step_(pause_step), pause_s_(pause_s) {}
  void step_completed(const CompletedStep& s) override;

 private:
  std::string run_dir_, node_;
  long every_;
  int keep_;
  std::function<NodeCheckpoint()> take_;
  std::optional<std::uint64_t> pause_step_;
  double pause_s_;
};

}  // namespace mechsim::cosim
