#include "exchanged_variables.h"

#include <algorithm>
#include <cstdlib>

namespace mechsim::fmi {

ExchangedVariables exchanged_variables(const ModelDescription& md) {
  ExchangedVariables out;
  for (const auto& v : md.variables) {
    if (v.type == ValueType::other) continue;
    if (v.causality == Causality::input) out.inputs.push_back(&v);
    if (v.causality == Causality::output) out.outputs.push_back(&v);
  }
  return out;
}

std::vector<int> feedthrough(const ModelDescription& md, const Variable& output,
                             const std::vector<const Variable*>& inputs) {
  const OutputDependencies* listed = md.find_output_dependencies(static_cast<int>(&output - md.variables.data()));
  std::vector<int> out;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const int input = static_cast<int>(inputs[i] - md.variables.data());
    bool depends = true;
    if (listed && listed->dependencies)
      depends = std::find(listed->dependencies->begin(), listed->dependencies->end(), input) != listed->dependencies->end();
    if (depends) out.push_back(static_cast<int>(i));
  }
  return out;
}

std::string port_unit(const Variable& v) { return v.unit.empty() ? "1" : v.unit; }

double start_value(const Variable& v, const FmuLabel& label) {
  if (!v.start) return 0.0;
  const std::string& s = *v.start;
  if (v.type == ValueType::boolean) return s == "true" || s == "1" ? 1.0 : 0.0;
  char* end = nullptr;
  const double value = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0')
    throw FmuError(label, "modelDescription.xml: variable '" + v.name + "': start '" + s + "' is not a number");
  return value;
}

void check_parameters(const ModelDescription& md, const std::map<std::string, double>& parameters,
                      const FmuLabel& label) {
  for (const auto& [name, value] : parameters) {
    const Variable* v = md.find_variable(name);
    if (v == nullptr) throw FmuError(label, "has no variable '" + name + "' (a parameter set in the scene)");
    if (v->causality != Causality::parameter || v->type == ValueType::other)
      throw FmuError(label, "variable '" + name + "' has causality " + std::string(to_string(v->causality)) +
                                " and type " + v->type_element +
                                "; the scene sets parameters of type Real/Float64, Integer/Int32 or Boolean");
  }
}

std::unique_ptr<FmuInstance> initialize(const FmuArchive& archive, InterfaceKind kind,
                                        const std::map<std::string, double>& parameters, double t0, double t_stop) {
  const FmuLabel& label = archive.label();
  check_parameters(archive.description(), parameters, label);
  auto fmu = FmuInstance::create(archive, kind, label.participant.empty() ? "fmu" : label.participant);
  fmu->enter_initialization(t0, t_stop);
  for (const auto& [name, value] : parameters) set_value(*fmu, *archive.description().find_variable(name), value);
  fmu->exit_initialization();
  return fmu;
}

void set_value(FmuInstance& fmu, const Variable& v, double value) {
  switch (v.type) {
    case ValueType::real: fmu.set_real(v.value_reference, value); break;
    case ValueType::integer: fmu.set_integer(v.value_reference, static_cast<std::int32_t>(value)); break;
    case ValueType::boolean: fmu.set_boolean(v.value_reference, value != 0.0); break;
    case ValueType::other: break;
  }
}

double get_value(FmuInstance& fmu, const Variable& v) {
  switch (v.type) {
    case ValueType::real: return fmu.get_finite_real(v);
    case ValueType::integer: return fmu.get_integer(v.value_reference);
    case ValueType::boolean: return fmu.get_boolean(v.value_reference) ? 1.0 : 0.0;
    case ValueType::other: break;
  }
  return 0.0;
}

}  // namespace mechsim::fmi
