// A mechsim participant as the core of a co-simulation FMU (`mechsim fmu export`,
// docs/fmi.md "Exporting mechsim models as FMUs"): the node type's block, built from the
// scene's `params:` exactly as the node builds it (cosim::NodeType::make_block), with its
// own integrator (solve::BlockIntegrator, the participant's `solver:`) inside do_step.
//
// The configuration travels inside the FMU as resources/participant.yaml (ExportConfig):
// the binary is the same for every exported participant; what it plays is data. The
// FMU's variables (ExportedVariable) are derived from that configuration alone, by the
// exporter (for modelDescription.xml) and by the binary (to serve value references), with
// the same code, so the two always agree:
//   value reference 0        time (FMI 3's independent variable; unused in FMI 2)
//   1 .. ni                  the block's inputs, in port order (start: the port's default;
//                            named `<name>_in` where an output has the same name)
//   then no                  the block's outputs, in port order
//   then np                  parameters: every numeric leaf of `params:` ("position_gain",
//                            "setpoint.distance"), in SI, start = the scene's value
//
// Stepping, as the node does it (cosim::NodeStepper::step): the inputs set before
// do_step(t, h) are held over [t, t+h]; the integrator restarts at t (the inputs start
// afresh) and stops at t+h; a discontinuity the block schedules (a setpoint step) inside
// the step is a stop and a restart too, as the run's step grid lands a boundary on it. The
// outputs are the block's at the current time with the inputs set last (direct feedthrough
// is seen at once). A sampled block takes its t0 sample when initialization ends.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/config_node.h"
#include "mechsim/config/scene.h"
#include "mechsim/models/block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::fmi_export {

// What resources/participant.yaml holds.
struct ExportConfig {
  std::string participant;  // the scene's instance name ("servo")
  std::string type;         // the node type ("servo_amplifier")
  std::string scene;        // the scene file it came from, for messages
  config::SolverSpec solver;
  config::ConfigNode params;  // the participant's `params:` (with --set overrides applied)
  // The element at the cut of a connection to or from the participant (a compliant
  // coupling's spring-damper), which its node type builds into the block as the plan does.
  std::optional<config::ConfigNode> coupling;
  // The scene's start, end and macro step, for the description's <DefaultExperiment>
  // (not written to participant.yaml: the binary does not need them).
  std::optional<config::TimeSpec> time;
};

std::string write_export_config(const ExportConfig& config);
// Reads it back; `file` labels errors. Throws config::ConfigError.
ExportConfig read_export_config(const std::string& text, const std::string& file);

enum class VariableKind { input, output, parameter };

struct ExportedVariable {
  std::string name;
  VariableKind kind;
  int index = 0;          // port index (input, output) or parameter index
  std::string unit;       // SI unit name; "" when none is known (a bare number in the scene)
  double start = 0.0;     // inputs and parameters
  std::string description;
};

// The dimension of a unit name as the variables carry it, for <UnitDefinitions>: the
// exponents over (m, kg, s, A, rad) and the factor to SI; nullopt when mechsim's unit
// parser does not know the name.
struct UnitDefinition {
  std::string name;
  config::Dimension dimension;
  double factor = 1.0;
};
std::vector<UnitDefinition> unit_definitions(const std::vector<ExportedVariable>& variables);

class ExportedParticipant {
 public:
  // Builds the block once (refusing bad parameters with the node type's message) and
  // derives the variables.
  explicit ExportedParticipant(ExportConfig config);
  ~ExportedParticipant();

  const ExportConfig& config() const { return config_; }
  const std::vector<ExportedVariable>& variables() const { return variables_; }
  const models::Block& block() const { return *block_; }
  // The variable of a value reference, nullptr when there is none (0 = time is none here).
  const ExportedVariable* variable(unsigned value_reference) const;
  static constexpr unsigned kTimeValueReference = 0;
  static unsigned value_reference(std::size_t variable_index) { return static_cast<unsigned>(variable_index + 1); }

  // --- lifecycle, in the FMI order ---------------------------------------------------
  // Parameters may be set until initialization ends; inputs at any time.
  void set_real(unsigned value_reference, double value);
  double get_real(unsigned value_reference);
  // stop_time: +inf when the importer gives none (the block's scheduled discontinuities are
  // then looked up step by step).
  void enter_initialization(double start_time, double stop_time);
  void exit_initialization();
  // Integrates [t, t+h] with the inputs held; t must be the current time.
  void do_step(double t, double h);
  double time() const { return t_; }
  bool initialized() const { return integrator_ != nullptr; }

  // FMU state (fmiXGet/SetFMUstate, fmiXSerializeFMUstate): time, integrator state, the
  // block's discrete state (mode, samples) and the inputs set last. Since every step
  // restarts the integrator at its start, a participant set back to a state continues
  // exactly as it did from there: same bytes. Only after initialization ends.
  struct State {
    double t = 0.0;
    std::vector<double> x, discrete, u;
  };
  State state() const;
  void set_state(const State& s);
  // Serialized: doubles, each field preceded by its length.
  static std::vector<unsigned char> serialize(const State& s);
  static State deserialize(const unsigned char* bytes, std::size_t size);

 private:
  void rebuild_block();
  void refresh_outputs();

  ExportConfig config_;
  std::unique_ptr<models::Block> block_;
  std::vector<ExportedVariable> variables_;
  std::vector<std::string> parameter_paths_;  // dotted path of each parameter under params
  std::vector<double> parameters_;
  bool parameters_changed_ = false;
  bool initializing_ = false;
  std::unique_ptr<solve::BlockIntegrator> integrator_;
  std::vector<double> u_, y_, x0_;
  std::vector<double> scheduled_;  // the block's scheduled discontinuities in (t0, stop), ascending
  double stop_time_ = 0.0;
  bool outputs_stale_ = true;
  double t_ = 0.0;
};

}  // namespace mechsim::fmi_export
