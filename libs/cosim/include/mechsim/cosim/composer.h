// The monolithic composer: every block of a scene wired into one ODE, as one block, so
// that the reference differs from the co-simulation only in the coupling (the blocks are
// the same objects). Inputs are fed by the partners' current outputs (no delay, no
// reconstruction); outputs are evaluated in an order that respects direct feedthrough.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/models/block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::cosim {

class CompositeBlock final : public models::Block {
 public:
  // The plan must outlive the composite. Outputs are named "<participant>.<output>".
  explicit CompositeBlock(ScenePlan& plan);

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  int num_event_functions() const override { return event_base_.back(); }
  models::Crossing event_direction(int index) const override;
  void event_functions(double t, std::span<const double> x, std::span<const double> u,
                       std::span<double> g) const override;
  bool handle_events(double t, std::span<double> x, std::span<const double> u,
                     std::span<const int> crossed) override;
  // Sampled blocks keep their own sample times: the composite samples at the shortest and
  // updates each block at its own instants (every sample time must be a whole multiple of
  // the shortest).
  double sample_time() const override { return sample_time_; }
  void discrete_update(double t, std::span<double> x, std::span<const double> u) override;
  // Events of every block, with the kind prefixed by the participant ("follower.lift_off").
  std::vector<models::BlockEvent> take_event_log() override;
  std::vector<double> save_discrete_state() const override;
  void restore_discrete_state(std::span<const double> saved) override;

  // First output column of participant i in the composite's outputs.
  int output_base(std::size_t participant) const { return output_base_[participant]; }

 private:
  struct Wire { int input, source_block, source_output; };
  // An interface-Jacobian cut: the composer evaluates its spring-damper once, from both
  // sides' angle and speed outputs, and feeds the torque to both torque inputs.
  struct CutWire { int plus_block, minus_block; const PlannedCut* plus; const PlannedCut* minus; };
  std::vector<CutWire> cuts_;
  // Evaluates all outputs (and with them all inputs) at (t, x) into y_/u_ scratch.
  void evaluate(double t, std::span<const double> x) const;
  std::span<const double> block_state(std::span<const double> x, std::size_t i) const;

  ScenePlan& plan_;
  std::vector<std::vector<Wire>> wires_;        // per block
  std::vector<int> state_base_, output_base_, event_base_;
  int passes_ = 1;
  double sample_time_ = 0.0;
  std::vector<long> sample_ratio_;              // per block: its sample time / sample_time_, 0 = continuous
  long samples_taken_ = 0;                      // discrete updates of the composite so far                              // evaluation sweeps needed for feedthrough chains
  mutable std::vector<std::vector<double>> u_, y_;
};

struct ReferenceRun {
  OutputLog log;             // t and every "<participant>.<output>" at every macro step
  solve::SolverStats stats;
  std::vector<models::BlockEvent> events;  // kinds prefixed by the participant ("follower.lift_off")
  double wall_time_s = 0.0;
  double rtol = 0.0;
  double atol = 0.0;
};

// Integrates the composed scene over its time span at tight tolerance, sampling the outputs
// at the macro-step grid t_k = t0 + k H. A scene with an adaptive step has no grid before its
// run: std::invalid_argument (use the overload with the run's instants).
ReferenceRun run_reference(ScenePlan& plan, double rtol = 1e-10, double atol = 1e-12);
// The same, sampled at the given instants (ascending, the first the scene's start): those a
// run with an adaptive step took (the t column of a node's output log).
ReferenceRun run_reference_at(ScenePlan& plan, std::span<const double> instants, double rtol = 1e-10, double atol = 1e-12);
// The instants the reference of a run samples: the grid's, or for an adaptive step those of
// the node logs in `run_dir` (every node logs the same).
std::vector<double> run_instants(const ScenePlan& plan, const std::string& run_dir);

// The reference's own error, estimated as its difference from a re-run of the scene at a
// tighter tolerance (rtol and atol divided by `factor`): while the integration error falls
// with the tolerance, the tight run is `factor` times closer to the exact solution, so the
// difference is the reference's error to within 1/factor of itself. A co-simulation error
// below this figure cannot be told apart from the reference's own error.
struct ReferenceAccuracy {
  double rtol = 0.0, atol = 0.0;     // of the tighter run
  double wall_time_s = 0.0;          // of the tighter run
  solve::SolverStats stats;          // of the tighter run
  std::vector<std::string> columns;  // "<participant>.<output>", as ReferenceRun::log (without "t")
  std::vector<double> max_abs, rms_abs;  // per column: max and RMS of |reference - tighter run|
  // Max difference of one column; NaN when unknown.
  double max_abs_of(const std::string& column) const;
  double rms_abs_of(const std::string& column) const;
};

// Re-runs the scene of `ref` (a fresh plan: the blocks of `plan` keep their run's state) at
// rtol/factor, atol/factor and compares every output column on the macro-step grid.
ReferenceAccuracy estimate_reference_error(const config::Scene& scene, const ReferenceRun& ref, double factor = 100.0);

}  // namespace mechsim::cosim
