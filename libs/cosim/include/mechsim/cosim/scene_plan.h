// A scene resolved against the node catalog: every participant's block built from its
// params, its topic, and its inbound edges with the field -> input mapping. Building the
// plan is the validation a launch does before any process starts: unknown node types,
// connections between types that cannot talk, unconnected required inputs, cycles of
// Gauss-Seidel edges and algebraic loops are refused with the file and key path.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/catalog/catalog.h"
#include "mechsim/cosim/step_grid.h"

namespace mechsim::cosim {

struct FmuParticipant;  // fmu_participant.h

struct InboundEdge {
  std::string from;                         // publishing participant
  std::string topic;                        // its topic name
  const transport::TopicType* type = nullptr;
  std::vector<std::pair<int, int>> field_to_input;  // (topic field index, block input index)
  config::EdgeOrder order = config::EdgeOrder::jacobi;
  config::Reconstruction reconstruction = config::Reconstruction::hold;
  std::vector<std::pair<int, double>> initial_values;  // (topic field index, SI value): a Jacobi
                                                       // edge's values before the first sample
};

// This node's side of a cut joined by the interface-Jacobian scheme (a connection with
// `coupling: {scheme: interface_jacobian}`): no state fields cross it; each side publishes a
// CouplingPrediction on "<name>/coupling" every step and reads the partner's.
struct PlannedCut {
  std::string partner;                       // the other participant of the cut
  std::string topic, partner_topic;          // "<name>/coupling", "<partner>/coupling"
  const transport::TopicType* type = nullptr;  // CouplingPrediction
  int torque_input = -1, angle_output = -1, speed_output = -1;  // of this node's block
  int twist_sign = 1;                        // +1: the torque loads this side; -1: it drives it
  int levels = 10;                           // torque levels per macro step
  double stiffness = 0.0, damping = 0.0;     // the coupling element
  std::string key_path;                      // "connections[3].coupling"
};

struct PlannedNode {
  const config::ParticipantSpec* spec = nullptr;
  const NodeType* type = nullptr;
  // `type: fmu`: the FMU and the node type made for it alone (`type` points into it).
  std::shared_ptr<const FmuParticipant> fmu;
  // A co-simulation FMU (type: fmu, or in place of a native block): it steps itself at its
  // own step, in the run and inside the monolithic reference alike, which therefore has no
  // continuous model of it (the error report says so).
  bool steps_itself = false;
  std::unique_ptr<models::Block> block;
  std::string topic;                    // "<name>/<suffix>"
  std::vector<int> published_outputs;   // block output index of each topic field, -1: not computed (NaN)
  std::vector<InboundEdge> inputs;
  int subscriber_count = 0;             // participants that read `topic`
  bool recorded = false;                // the launcher's recorder reads `topic` too (scene `record:`)
  std::optional<PlannedCut> cut;        // interface-Jacobian cut, if this node is on one
  // The outputs whose error matters beyond this node: compared with the reference (scene
  // `compare:`) or read by another participant. The adaptive step weighs a Jacobi input's
  // error by its effect on these (step_control.h).
  std::vector<int> watched_outputs;
  // Adaptive step: angles [rad, in [0, 2 pi)] at which the block's law jumps or kinks that
  // the plan could not turn into times, since the shaft's speed varies (angle_event_prediction.h).
  // The node predicts them at run time from the shaft's `angle`, `speed` and `acceleration`:
  // its block's inputs (a follower's load boundaries) or its own outputs (a cam's law joints).
  struct RunTimeAngleEvents {
    bool own_outputs = false;
    std::vector<double> angles;
  };
  std::vector<RunTimeAngleEvents> run_time_angle_events;
  const std::string& name() const { return spec->name; }
};

class ScenePlan {
 public:
  // Throws config::ConfigError. A scene made for an analysis (its `design:` section) that
  // cannot be run in time says which command it is for.
  static ScenePlan build(const config::Scene& scene);

  const config::Scene& scene() const { return *scene_; }
  // The run's macro-step instants, the same for every node, the reference and the tools:
  // the scene's uniform grid, landed on the participants' scheduled events.
  const std::shared_ptr<const StepGrid>& grid() const { return grid_; }
  struct ScheduledEvent {
    std::string participant;
    double t = 0.0;  // s
  };
  // What the participants' blocks announced before the run (models::Block::scheduled_events).
  const std::vector<ScheduledEvent>& scheduled_events() const { return scheduled_events_; }
  std::vector<PlannedNode>& nodes() { return nodes_; }
  const std::vector<PlannedNode>& nodes() const { return nodes_; }
  const PlannedNode& node(const std::string& name) const;
  PlannedNode& node(const std::string& name);
  // The published quantities whose scale an adaptive step's estimate uses (time.scales,
  // step_control.h), as (participant, field): every field a node reads, and every watched
  // output a node publishes. Each once, in plan order.
  std::vector<std::pair<std::string, std::string>> scaled_quantities() const;
  // (node index, output index) of a compared signal; throws ConfigError if unknown.
  std::pair<int, int> resolve(const config::SignalRef& ref) const;

 private:
  // The passes, in order (scene_plan.cpp): every participant's block and topic; the
  // connections as inbound edges and cuts; the outputs that matter beyond their node;
  // required inputs fed; Gauss-Seidel edges without cycles; no algebraic loop; compared and
  // reported signals and time.scales known; then the step grid.
  static ScenePlan build_time_run(const config::Scene& scene);
  void place_nodes();
  void resolve_edges();
  void mark_watched_outputs();
  void check_required_inputs() const;
  void order_gauss_seidel() const;
  void check_algebraic_loops() const;
  void resolve_signals() const;
  int index_of(const std::string& name) const;  // -1: no such participant
  // Collects the blocks' scheduled events (and their angle events where a uniformly turning
  // shaft feeds them) and lands the grid on them.
  void land_on_scheduled_events();
  const config::Scene* scene_ = nullptr;
  std::shared_ptr<const StepGrid> grid_;
  std::vector<ScheduledEvent> scheduled_events_;
  std::vector<PlannedNode> nodes_;
};

}  // namespace mechsim::cosim
