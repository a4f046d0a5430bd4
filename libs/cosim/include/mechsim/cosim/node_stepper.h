// The lock-step protocol of one node, without transport: holds the node's block, its
// integrator and one InputChannel per inbound edge, and advances k -> k+1 when the
// channels hold what the step needs. The transport loop (NodeRunner) feeds the channels
// and publishes what step() returns; tests drive two steppers by hand.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "mechsim/cosim/angle_event_prediction.h"
#include "mechsim/cosim/coupling/interface_jacobian.h"
#include "mechsim/cosim/input_channel.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/step_control.h"
#include "mechsim/cosim/step_grid.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::cosim {

solve::SolverOptions solver_options(const config::SolverSpec& spec);

// A node's complete state at a step boundary, with the step keys of its channels' samples:
// what a checkpoint stores (checkpoint.h) so that a node, restored in this process or in a
// new one, goes on exactly as it would have.
struct StepperSnapshot {
  std::uint64_t step = 0;
  std::vector<double> state;     // the integrator's (it restarts at every macro step)
  std::vector<double> discrete;  // the block's sampled / held / mode state
  std::vector<double> outputs;   // all block outputs at `step`
  // Per channel, the samples of steps before `step` it still needs (the partners publish
  // `step` and later again after a rollback).
  std::vector<std::vector<std::pair<std::uint64_t, std::vector<double>>>> channels;
  double assumed_torque = 0.0;   // interface-Jacobian cut: what the next prediction assumes
};

class NodeStepper {
 public:
  // `node` must outlive the stepper (it owns the block). `grid`: the plan's (ScenePlan::grid),
  // the same for every node of the run. With an adaptive grid, `participants` nodes agree
  // on each step and this one is number `self` of them (the plan's node order).
  NodeStepper(PlannedNode& node, std::shared_ptr<const StepGrid> grid, std::size_t participants = 1, std::size_t self = 0);
  const StepGrid& grid() const { return *grid_; }

  InputChannel& channel(std::size_t edge) { return channels_[edge]; }
  std::size_t channel_count() const { return channels_.size(); }

  // Step index of the outputs published last (after initialise(): 0).
  std::uint64_t step() const { return k_; }
  double time() const;
  bool finished() const { return initialised_ && grid_->at_end(k_); }

  bool can_initialise() const;
  // Computes the step-0 outputs. `topic_values` receives the published fields.
  void initialise(std::vector<double>& topic_values);
  bool can_step() const;
  // Integrates over [t_k, t_k+1] and computes the step-(k+1) outputs.
  void step(std::vector<double>& topic_values);

  // Interface-Jacobian cut (node().cut): before step k -> k+1 the node publishes its
  // prediction for that step on the cut's topic (step index k), once every other input of
  // the step is there; the step then waits for the partner's prediction of step k.
  bool prediction_due() const;
  void predict(std::vector<double>& prediction_fields);
  void add_partner_prediction(std::uint64_t step, std::span<const double> fields);

  // Adaptive macro step (grid().is_adaptive(); step_control.h): after its step-k outputs, once
  // its Jacobi partners' step-k samples are there, the node proposes the length of step
  // k -> k+1 and publishes the proposal on <node>/step; the step (and an interface-Jacobian
  // prediction) waits until every participant's proposal of step k is there, when the grid
  // gains t_k+1. add_proposal throws std::runtime_error when a participant proposes two
  // different things for one step (a foreign writer).
  bool proposal_due() const;
  StepProposal propose();
  void add_proposal(std::size_t participant, std::uint64_t step, const StepProposal& proposal);
  std::size_t participant_index() const { return self_; }
  // The participants (plan indices) whose proposal the next step still waits for; empty when
  // the step is agreed or the run has a fixed step.
  std::vector<std::size_t> missing_proposals() const;

  // All block outputs at the current step (for the run folder), and solver statistics.
  const std::vector<double>& outputs() const { return y_; }
  // After step() from an event instant t_k (grid().is_event(k)): the outputs to log for t_k,
  // evaluated on the event's far side with the inputs of the step just taken at its start
  // (a held or extrapolated Jacobi input is then the partner's step-k sample, computed after
  // the event). The published step-k sample stays what it was. nullptr after other steps.
  // A node on an interface-Jacobian cut logs its step-k outputs unchanged.
  const std::vector<double>* event_row() const { return event_row_ready_ ? &event_row_ : nullptr; }
  const solve::SolverStats* solver_stats() const { return integrator_ ? &integrator_->stats() : nullptr; }
  std::vector<solve::EventRecord> take_events();

  // The node's part of the coupled state at a step boundary (after step(), before the next
  // prediction), for the linear analysis of the macro-step map (tools/bench/stability.cpp):
  // its integrator state, its block's discrete (sampled, held) state, then every sample its channels hold (channel by channel, oldest
  // step first), then the torque an interface-Jacobian cut assumes next. set_coupled_state
  // writes the same layout back (the integrator restarts from the new state); throws
  // std::invalid_argument on a size mismatch.
  std::vector<double> coupled_state() const;
  void set_coupled_state(std::span<const double> z);

  // The state at the current step boundary (after initialise() or step(), before the next
  // prediction), and its restoration: in a stepper of the same node, initialised or not.
  // restore() fills `topic_values` with the restored step's published fields (sent again
  // on resume) and drops every partner prediction; the next prediction is made afresh.
  StepperSnapshot snapshot() const;
  void restore(const StepperSnapshot& s, std::vector<double>& topic_values);

 private:
  void inputs_at(double t, std::uint64_t k, std::span<double> u);
  void initial_inputs(std::span<double> u);
  void publishable(std::vector<double>& topic_values) const;

  bool inputs_ready(std::uint64_t k) const;
  bool step_known() const { return grid_->knows_end_of(k_); }
  void agree_if_complete();

  PlannedNode& node_;
  // Interface-Jacobian cut: this side, its prediction for step k_ (if made), the partner's
  // predictions by step, and the torque the next prediction assumes (the last solved level).
  std::unique_ptr<coupling::InterfaceSide> cut_side_;
  coupling::InterfacePrediction own_prediction_;
  bool has_own_prediction_ = false;
  std::map<std::uint64_t, coupling::InterfacePrediction> partner_predictions_;
  // Map nodes of used partner predictions, kept for reuse (no allocation per step).
  std::vector<std::map<std::uint64_t, coupling::InterfacePrediction>::node_type> spare_predictions_;
  std::vector<double> levels_;
  double assumed_torque_ = 0.0, end_torque_ = 0.0;
  std::shared_ptr<const StepGrid> grid_;
  std::vector<InputChannel> channels_;
  std::unique_ptr<solve::BlockIntegrator> integrator_;
  std::vector<double> defaults_, u_, y_, x_, scratch_;
  std::vector<double> event_inputs_, event_row_;
  bool event_row_ready_ = false;
  std::uint64_t k_ = 0;
  bool initialised_ = false;
  // Adaptive macro step: this node's estimate, the proposals of the step being agreed.
  std::size_t self_ = 0;
  std::optional<CouplingErrorEstimate> estimate_;
  std::optional<StepAgreement> agreement_;
  std::uint64_t proposed_step_ = UINT64_MAX;  // the step this node proposed for last
  // Scratch for measuring an input edge's effect on the watched outputs (propose).
  std::vector<double> effect_u_, effect_y_, effect_change_;
  // Roots the integrator found while stepping (take_events), and the last of them with the
  // step it ended (a state event the next proposal reports).
  std::vector<solve::EventRecord> found_events_;
  std::uint64_t state_event_step_ = UINT64_MAX;
  double state_event_time_ = 0.0;
  // Run-time angle events (PlannedNode::run_time_angle_events): where the shaft's angle,
  // speed and acceleration are (block inputs or own outputs; -1: none), the last crossing
  // announced, and the last one landed on (so that one crossing is landed once).
  struct AngleWatch {
    const std::vector<double>* angles = nullptr;
    bool own_outputs = false;
    int angle = -1, speed = -1, acceleration = -1;
    PredictedAngleEvent announced;
    double passed = -std::numeric_limits<double>::infinity();
  };
  std::vector<AngleWatch> angle_watches_;
  double next_angle_event(double t_next);
  // A sampled block's first tick (t0 + j sample_time, the integrator's own instants) more
  // than `min` after t_next; +inf for a continuous block.
  double next_sample_tick(double t_next) const;
};

}  // namespace mechsim::cosim
