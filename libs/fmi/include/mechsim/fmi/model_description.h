// modelDescription.xml of an FMI 2.0 or 3.0 FMU, read into plain structs: what `mechsim fmu
// info` prints and what the importer needs to call the binary (identifiers, value
// references, state and event-indicator counts). Variables of types mechsim does not
// exchange (String, Enumeration, Float32, ..., arrays) are kept with ValueType::other so
// that they are listed, never connected.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mechsim/fmi/error.h"

namespace mechsim::fmi {

enum class FmiVersion { fmi2, fmi3 };
enum class InterfaceKind { co_simulation, model_exchange };
enum class Causality { parameter, calculated_parameter, structural_parameter, input, output, local, independent };
enum class Variability { constant, fixed, tunable, discrete, continuous };
enum class ValueType { real, integer, boolean, other };  // Real/Float64, Integer/Int32, Boolean

std::string_view to_string(FmiVersion v);     // "2.0", "3.0"
std::string_view to_string(InterfaceKind k);  // "co-simulation", "model-exchange"
std::string_view to_string(Causality c);      // as in the standard: "calculatedParameter", ...
std::string_view to_string(Variability v);
std::string_view to_string(ValueType t);      // "real", "integer", "boolean", "other"

// One interface the FMU offers (<CoSimulation> or <ModelExchange>) and its capability flags.
struct Interface {
  InterfaceKind kind = InterfaceKind::co_simulation;
  std::string model_identifier;  // the shared object's name, binaries/<platform>/<id>.so
  bool needs_execution_tool = false;
  bool can_get_and_set_state = false;        // canGetAndSetFMUstate (2) / canGetAndSetFMUState (3)
  bool can_serialize_state = false;          // canSerializeFMUstate (2) / canSerializeFMUState (3)
  bool provides_directional_derivatives = false;
  bool can_handle_variable_step = false;     // co-simulation only
};

struct Variable {
  std::string name;
  std::uint32_t value_reference = 0;
  Causality causality = Causality::local;
  Variability variability = Variability::continuous;
  ValueType type = ValueType::other;
  std::string type_element;           // the element as written: Real, Float64, String, Float32, ...
  std::string unit;                   // own unit, else the declared type's; "" when none
  std::string declared_type;
  std::optional<std::string> start;   // as written in the file
  std::string description;
};

// <Unit> of <UnitDefinitions>: SI base-unit exponents, factor and offset (value in SI =
// factor * value + offset), for checking units against the other side of a connection.
struct UnitDefinition {
  std::string name;
  int kg = 0, m = 0, s = 0, A = 0, K = 0, mol = 0, cd = 0, rad = 0;
  double factor = 1.0, offset = 0.0;
};

// An output of <ModelStructure> (FMI 2 <Outputs><Unknown>, FMI 3 <Output>) and what it
// depends on: indices into ModelDescription::variables (inputs, states, ...). nullopt where
// the description gives no `dependencies` attribute: then it may depend on everything.
struct OutputDependencies {
  int variable = -1;
  std::optional<std::vector<int>> dependencies;
};

struct ModelDescription {
  FmiVersion version = FmiVersion::fmi2;
  std::string fmi_version;             // the attribute as written ("2.0", "3.0")
  std::string model_name;
  std::string instantiation_token;     // guid (2) / instantiationToken (3)
  std::string generation_tool;
  std::vector<Interface> interfaces;
  std::vector<Variable> variables;
  std::vector<UnitDefinition> units;
  int number_of_continuous_states = 0;  // from ModelStructure (derivatives)
  // The continuous states in the FMU's order: the variables the listed derivatives are the
  // derivatives of (index into `variables`; -1 where the description does not say).
  std::vector<int> state_variables;
  int number_of_event_indicators = 0;
  std::vector<OutputDependencies> output_dependencies;
  std::optional<double> default_start_time, default_stop_time, default_tolerance, default_step_size;

  const Interface* find_interface(InterfaceKind kind) const;
  const Variable* find_variable(std::string_view name) const;
  const UnitDefinition* find_unit(std::string_view name) const;
  // The <ModelStructure> entry of variable index `variable`, nullptr when it has none.
  const OutputDependencies* find_output_dependencies(int variable) const;
};

// Parses the text of modelDescription.xml. Refuses (FmuError naming `label`) malformed XML
// (with the parser's line and column), a file that is not an FMI model description, FMI 1.0
// and any version other than 2.0 / 3.0, and variables without name or value reference.
ModelDescription parse_model_description(std::string_view xml, const FmuLabel& label);

}  // namespace mechsim::fmi
