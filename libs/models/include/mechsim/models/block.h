// The one abstraction for every model: a continuous-time block with named ports.
//
// A block declares its inputs, outputs and continuous states in its constructor (the
// constructor is the declaration, as in Drake's LeafSystem) and then only computes:
//   derivatives(t, x, u) -> dx/dt     calc_outputs(t, x, u) -> y
// plus, optionally, zero-crossing event functions with a handler (follower lift-off),
// a sampled (discrete) update, and a discrete "mode" state that is saved with the
// continuous state for checkpoints.
//
// The same block object runs inside a node process (integrated by SUNDIALS between
// exchanges) and inside the monolithic composer that builds the reference. Blocks never
// see DDS, YAML or files: parameters arrive as plain structs.
#pragma once

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mechsim::models {

struct InputPort {
  std::string name;
  std::string unit;       // SI unit, for documentation and CSV headers
  double default_value;   // used when the scene leaves the input unconnected
  bool required;          // an unconnected required input is refused at launch
};

struct OutputPort {
  std::string name;
  std::string unit;
  // Inputs (by index) that reach this output without passing through a state: direct
  // feedthrough. The composer orders output evaluation by it and refuses algebraic loops.
  std::vector<int> feedthrough;
};

// Something a block reports about an event it handled (a follower lift-off with its
// angle, a landing with its impact velocity), for the run summary and the node log.
struct BlockEvent {
  std::string kind;  // "lift_off", "landing", ...
  double t = 0.0;
  std::vector<std::pair<std::string, double>> values;  // name (with unit suffix) -> value
};

// Direction of a zero crossing that counts as an event.
enum class Crossing { any = 0, rising = 1, falling = -1 };

class Block {
 public:
  virtual ~Block() = default;
  Block(const Block&) = delete;
  Block& operator=(const Block&) = delete;

  const std::string& type_name() const { return type_name_; }
  const std::vector<InputPort>& inputs() const { return inputs_; }
  const std::vector<OutputPort>& outputs() const { return outputs_; }
  const std::vector<std::string>& state_names() const { return state_names_; }
  int num_inputs() const { return static_cast<int>(inputs_.size()); }
  int num_outputs() const { return static_cast<int>(outputs_.size()); }
  int num_states() const { return static_cast<int>(state_names_.size()); }
  // Index of a port or state by name, -1 when there is none.
  int input_index(std::string_view name) const;
  int output_index(std::string_view name) const;
  int state_index(std::string_view name) const;
  // Default input vector (every port at its default value).
  std::vector<double> default_inputs() const;

  // --- continuous part -------------------------------------------------------------
  // x has num_states() entries, u num_inputs(), y num_outputs().
  virtual void initial_state(double t0, std::span<double> x) const;
  virtual void derivatives(double t, std::span<const double> x, std::span<const double> u,
                           std::span<double> dxdt) const;
  virtual void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                            std::span<double> y) const = 0;

  // --- events (zero crossings found by the integrator's root finding) -------------------
  virtual int num_event_functions() const { return 0; }
  virtual Crossing event_direction(int /*index*/) const { return Crossing::any; }
  virtual void event_functions(double /*t*/, std::span<const double> /*x*/,
                               std::span<const double> /*u*/, std::span<double> /*g*/) const {}
  // Called at an event time with crossed[i] = +1 (rising), -1 (falling) or 0. May switch
  // the block's mode and jump x. Returns true when x or the mode changed, so that the
  // integrator restarts from the new state.
  virtual bool handle_events(double /*t*/, std::span<double> /*x*/, std::span<const double> /*u*/,
                             std::span<const int> /*crossed*/) {
    return false;
  }

  // Events handled since the last call, described for people (see BlockEvent). A block
  // that reports events keeps them from handle_events until they are taken.
  virtual std::vector<BlockEvent> take_event_log() { return {}; }

  // --- sampled part -------------------------------------------------------------------
  // A sampled block returns its sample time (> 0); discrete_update is then called at
  // t0 + j * sample_time() before the continuous part is integrated onwards.
  virtual double sample_time() const { return 0.0; }
  virtual void discrete_update(double /*t*/, std::span<double> /*x*/, std::span<const double> /*u*/) {}

  // --- discontinuities known before the run -------------------------------------------
  // Instants in (t0, t_end) at which the block's own schedule makes its outputs or its
  // right-hand side jump or kink (a setpoint step or ramp corner, a ratio-schedule point),
  // whatever its inputs do. The run's step grid (libs/cosim/include/mechsim/cosim/step_grid.h)
  // lands a macro-step boundary on each, so that no exchange interval straddles one and the
  // sample at the instant is the value after it (the schedules are right-continuous). Default: none.
  virtual std::vector<double> scheduled_events(double /*t0*/, double /*t_end*/) const { return {}; }
  // The same in cam angle: angles [rad, in [0, 2 pi)] of the block's input `angle` at which
  // its law jumps (a functional load's ends). Where that input comes from a shaft turning
  // uniformly (uniform_rotation() of the publisher), the plan turns them into times, and
  // moves each time to the first double at which angle_event_reached() holds, so that the
  // block evaluates the sample at the event on its far side.
  virtual std::vector<double> angle_events() const { return {}; }
  virtual bool angle_event_reached(double theta, double event) const { return theta >= event; }
  // A shaft whose output `angle` is angle(t), computed exactly so, whatever its inputs.
  struct UniformRotation {
    double angle0 = 0.0;  // rad at t = 0
    double speed = 0.0;   // rad/s
    double angle(double t) const { return angle0 + speed * t; }
  };
  virtual std::optional<UniformRotation> uniform_rotation() const { return std::nullopt; }
  // Angles [rad, in [0, 2 pi)] of the block's own output `angle` at which its law changes
  // from one formula to the next without a jump (a cam law's joints: the torque of the
  // follower kinks there). A fixed grid takes no notice; an adaptive macro step lands on
  // them where the shaft turns uniformly and starts again from its initial length, since
  // the error of the step before says nothing of the piece after. Default: none.
  virtual std::vector<double> angle_law_changes() const { return {}; }
  // A block that knows the run's instants ahead (the replay of a run with an adaptive macro
  // step) names the first after t: the step from t ends there. Default: +inf, none.
  virtual double next_instant_after(double /*t*/) const { return std::numeric_limits<double>::infinity(); }

  // --- checkpoints: the mode / discrete state that is not integrated ------------------
  virtual std::vector<double> save_discrete_state() const { return {}; }
  virtual void restore_discrete_state(std::span<const double> /*saved*/) {}

 protected:
  explicit Block(std::string type_name) : type_name_(std::move(type_name)) {}
  int declare_input(std::string name, std::string unit, double default_value);
  int declare_required_input(std::string name, std::string unit);
  int declare_output(std::string name, std::string unit, std::vector<int> feedthrough = {});
  int declare_state(std::string name, std::string unit);

 private:
  std::string type_name_;
  std::vector<InputPort> inputs_;
  std::vector<OutputPort> outputs_;
  std::vector<std::string> state_names_;
  std::vector<std::string> state_units_;
};

}  // namespace mechsim::models
