// modelDescription.xml with pugixml. FMI 2 (<ScalarVariable> with a typed child) and FMI 3
// (typed variable elements) are read into the same structs; the differences stay here.
#include "mechsim/fmi/model_description.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include <pugixml.hpp>

namespace mechsim::fmi {

std::string_view to_string(FmiVersion v) { return v == FmiVersion::fmi2 ? "2.0" : "3.0"; }
std::string_view to_string(InterfaceKind k) {
  return k == InterfaceKind::co_simulation ? "co-simulation" : "model-exchange";
}
std::string_view to_string(Causality c) {
  switch (c) {
    case Causality::parameter: return "parameter";
    case Causality::calculated_parameter: return "calculatedParameter";
    case Causality::structural_parameter: return "structuralParameter";
    case Causality::input: return "input";
    case Causality::output: return "output";
    case Causality::local: return "local";
    case Causality::independent: return "independent";
  }
  return "?";
}
std::string_view to_string(Variability v) {
  switch (v) {
    case Variability::constant: return "constant";
    case Variability::fixed: return "fixed";
    case Variability::tunable: return "tunable";
    case Variability::discrete: return "discrete";
    case Variability::continuous: return "continuous";
  }
  return "?";
}
std::string_view to_string(ValueType t) {
  switch (t) {
    case ValueType::real: return "real";
    case ValueType::integer: return "integer";
    case ValueType::boolean: return "boolean";
    case ValueType::other: return "other";
  }
  return "?";
}

const Interface* ModelDescription::find_interface(InterfaceKind kind) const {
  for (const auto& i : interfaces)
    if (i.kind == kind) return &i;
  return nullptr;
}
const Variable* ModelDescription::find_variable(std::string_view name) const {
  for (const auto& v : variables)
    if (v.name == name) return &v;
  return nullptr;
}
const UnitDefinition* ModelDescription::find_unit(std::string_view name) const {
  for (const auto& u : units)
    if (u.name == name) return &u;
  return nullptr;
}
const OutputDependencies* ModelDescription::find_output_dependencies(int variable) const {
  for (const auto& o : output_dependencies)
    if (o.variable == variable) return &o;
  return nullptr;
}

namespace {

struct Parser {
  const FmuLabel& label;
  FmiVersion version;

  [[noreturn]] void fail(const std::string& what) const {
    throw FmuError(label, "modelDescription.xml: " + what);
  }

  Causality causality(const pugi::xml_node& n, const std::string& var) const {
    const std::string c = n.attribute("causality").as_string("local");
    if (c == "parameter") return Causality::parameter;
    if (c == "calculatedParameter") return Causality::calculated_parameter;
    if (c == "structuralParameter" && version == FmiVersion::fmi3) return Causality::structural_parameter;
    if (c == "input") return Causality::input;
    if (c == "output") return Causality::output;
    if (c == "local") return Causality::local;
    if (c == "independent") return Causality::independent;
    fail("variable '" + var + "': unknown causality '" + c + "'");
  }

  Variability variability(const pugi::xml_node& n, const std::string& var, ValueType type) const {
    // The default is continuous for Real/Float variables, discrete for the others (both versions).
    const std::string d = type == ValueType::real ? "continuous" : "discrete";
    const std::string v = n.attribute("variability").as_string(d.c_str());
    if (v == "constant") return Variability::constant;
    if (v == "fixed") return Variability::fixed;
    if (v == "tunable") return Variability::tunable;
    if (v == "discrete") return Variability::discrete;
    if (v == "continuous") return Variability::continuous;
    fail("variable '" + var + "': unknown variability '" + v + "'");
  }

  std::uint32_t value_reference(const pugi::xml_node& n, const std::string& var) const {
    const auto a = n.attribute("valueReference");
    if (!a) fail("variable '" + var + "' has no valueReference");
    const std::string text = a.as_string();
    char* end = nullptr;
    const unsigned long long vr = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || text[0] == '-' || vr > 0xffffffffULL)
      fail("variable '" + var + "': valueReference '" + text + "' is not an unsigned 32-bit integer");
    return static_cast<std::uint32_t>(vr);
  }

  static std::optional<std::string> optional_text(const pugi::xml_attribute& a) {
    if (!a) return std::nullopt;
    return std::string(a.as_string());
  }

  static bool flag(const pugi::xml_node& n, const char* name) { return n.attribute(name).as_bool(false); }

  Interface read_interface(const pugi::xml_node& n, InterfaceKind kind) const {
    Interface i;
    i.kind = kind;
    i.model_identifier = n.attribute("modelIdentifier").as_string();
    if (i.model_identifier.empty())
      fail("<" + std::string(n.name()) + "> has no modelIdentifier");
    i.needs_execution_tool = flag(n, "needsExecutionTool");
    if (version == FmiVersion::fmi2) {
      i.can_get_and_set_state = flag(n, "canGetAndSetFMUstate");
      i.can_serialize_state = flag(n, "canSerializeFMUstate");
      i.provides_directional_derivatives = flag(n, "providesDirectionalDerivative");
    } else {
      i.can_get_and_set_state = flag(n, "canGetAndSetFMUState");
      i.can_serialize_state = flag(n, "canSerializeFMUState");
      i.provides_directional_derivatives = flag(n, "providesDirectionalDerivatives");
    }
    if (kind == InterfaceKind::co_simulation)
      i.can_handle_variable_step = flag(n, "canHandleVariableCommunicationStepSize");
    return i;
  }

  void read_units(const pugi::xml_node& root, ModelDescription& md) const {
    for (const auto& u : root.child("UnitDefinitions").children("Unit")) {
      UnitDefinition d;
      d.name = u.attribute("name").as_string();
      if (d.name.empty()) fail("<Unit> without a name in <UnitDefinitions>");
      if (const auto b = u.child("BaseUnit")) {
        d.kg = b.attribute("kg").as_int(0);
        d.m = b.attribute("m").as_int(0);
        d.s = b.attribute("s").as_int(0);
        d.A = b.attribute("A").as_int(0);
        d.K = b.attribute("K").as_int(0);
        d.mol = b.attribute("mol").as_int(0);
        d.cd = b.attribute("cd").as_int(0);
        d.rad = b.attribute("rad").as_int(0);
        d.factor = b.attribute("factor").as_double(1.0);
        d.offset = b.attribute("offset").as_double(0.0);
      }
      md.units.push_back(std::move(d));
    }
  }

  // Units of the declared types: <SimpleType name><Real unit/></SimpleType> (2),
  // <Float64Type name unit/> (3).
  std::vector<std::pair<std::string, std::string>> type_units(const pugi::xml_node& root) const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& t : root.child("TypeDefinitions").children()) {
      if (version == FmiVersion::fmi2) {
        if (std::string(t.name()) != "SimpleType") continue;
        out.emplace_back(t.attribute("name").as_string(), t.child("Real").attribute("unit").as_string());
      } else {
        out.emplace_back(t.attribute("name").as_string(), t.attribute("unit").as_string());
      }
    }
    return out;
  }

  static std::string lookup(const std::vector<std::pair<std::string, std::string>>& table, const std::string& key) {
    for (const auto& [k, v] : table)
      if (k == key) return v;
    return "";
  }

  void read_variables_fmi2(const pugi::xml_node& root, ModelDescription& md) const {
    const auto types = type_units(root);
    std::vector<int> derivative_of;  // per variable: the index of the variable it is the derivative of
    int index = 0;
    for (const auto& sv : root.child("ModelVariables").children("ScalarVariable")) {
      ++index;
      Variable v;
      v.name = sv.attribute("name").as_string();
      if (v.name.empty()) fail("ScalarVariable " + std::to_string(index) + " has no name");
      v.value_reference = value_reference(sv, v.name);
      v.description = sv.attribute("description").as_string();
      pugi::xml_node typed;
      for (const char* t : {"Real", "Integer", "Boolean", "String", "Enumeration"})
        if ((typed = sv.child(t))) break;
      if (!typed) fail("variable '" + v.name + "' has no type element (Real, Integer, Boolean, String, Enumeration)");
      v.type_element = typed.name();
      v.type = v.type_element == "Real"      ? ValueType::real
               : v.type_element == "Integer" ? ValueType::integer
               : v.type_element == "Boolean" ? ValueType::boolean
                                             : ValueType::other;
      v.causality = causality(sv, v.name);
      v.variability = variability(sv, v.name, v.type);
      v.declared_type = typed.attribute("declaredType").as_string();
      v.unit = typed.attribute("unit").as_string();
      if (v.unit.empty() && !v.declared_type.empty()) v.unit = lookup(types, v.declared_type);
      v.start = optional_text(typed.attribute("start"));
      derivative_of.push_back(typed.attribute("derivative").as_int(0) - 1);  // 1-based index -> 0-based
      md.variables.push_back(std::move(v));
    }
    // <Derivatives><Unknown index> (1-based into ModelVariables), in the states' order.
    for (const auto& unknown : root.child("ModelStructure").child("Derivatives").children("Unknown")) {
      const int derivative = unknown.attribute("index").as_int(0) - 1;
      const bool known = derivative >= 0 && derivative < static_cast<int>(derivative_of.size());
      const int state = known ? derivative_of[static_cast<std::size_t>(derivative)] : -1;
      md.state_variables.push_back(state >= 0 && state < static_cast<int>(md.variables.size()) ? state : -1);
    }
    md.number_of_continuous_states = static_cast<int>(md.state_variables.size());
    md.number_of_event_indicators = root.attribute("numberOfEventIndicators").as_int(0);
    // <Outputs><Unknown index dependencies> (1-based indices into ModelVariables).
    const auto variable_at = [&](long long index, const std::string& where) {
      if (index < 1 || index > static_cast<long long>(md.variables.size()))
        fail("<ModelStructure><Outputs>: " + where + " " + std::to_string(index) + " is not a ScalarVariable (1.." +
             std::to_string(md.variables.size()) + ")");
      return static_cast<int>(index - 1);
    };
    for (const auto& unknown : root.child("ModelStructure").child("Outputs").children("Unknown")) {
      OutputDependencies o;
      o.variable = variable_at(unknown.attribute("index").as_llong(0), "index");
      if (const auto d = unknown.attribute("dependencies"))
        o.dependencies = numbers(d.as_string(), [&](long long i) { return variable_at(i, "dependency"); });
      md.output_dependencies.push_back(std::move(o));
    }
  }

  // The whitespace-separated integers of an attribute, each mapped by `to_variable`.
  template <typename F>
  std::vector<int> numbers(const std::string& text, F to_variable) const {
    std::vector<int> out;
    std::size_t pos = 0;
    while (pos < text.size()) {
      if (std::isspace(static_cast<unsigned char>(text[pos]))) {
        ++pos;
        continue;
      }
      std::size_t used = 0;
      long long value = 0;
      try {
        value = std::stoll(text.substr(pos), &used);
      } catch (const std::exception&) {
        fail("<ModelStructure>: dependencies=\"" + text + "\" is not a list of integers");
      }
      out.push_back(to_variable(value));
      pos += used;
    }
    return out;
  }

  void read_variables_fmi3(const pugi::xml_node& root, ModelDescription& md) const {
    const auto types = type_units(root);
    std::vector<long long> derivative_of;  // per variable: the value reference it is the derivative of, -1
    int index = 0;
    for (const auto& e : root.child("ModelVariables").children()) {
      if (e.type() != pugi::node_element) continue;
      ++index;
      Variable v;
      v.name = e.attribute("name").as_string();
      if (v.name.empty()) fail("variable " + std::to_string(index) + " (<" + e.name() + ">) has no name");
      v.value_reference = value_reference(e, v.name);
      v.description = e.attribute("description").as_string();
      v.type_element = e.name();
      const bool array = static_cast<bool>(e.child("Dimension"));
      v.type = array                          ? ValueType::other
               : v.type_element == "Float64" ? ValueType::real
               : v.type_element == "Int32"   ? ValueType::integer
               : v.type_element == "Boolean" ? ValueType::boolean
                                             : ValueType::other;
      if (array) v.type_element += "[]";
      v.causality = causality(e, v.name);
      v.variability = variability(e, v.name, v.type_element.starts_with("Float") ? ValueType::real : v.type);
      v.declared_type = e.attribute("declaredType").as_string();
      v.unit = e.attribute("unit").as_string();
      if (v.unit.empty() && !v.declared_type.empty()) v.unit = lookup(types, v.declared_type);
      v.start = optional_text(e.attribute("start"));
      const auto derivative = e.attribute("derivative");
      derivative_of.push_back(derivative ? static_cast<long long>(derivative.as_ullong()) : -1);
      md.variables.push_back(std::move(v));
    }
    const auto index_of_reference = [&](long long vr) {
      for (std::size_t i = 0; i < md.variables.size(); ++i)
        if (md.variables[i].value_reference == vr) return static_cast<int>(i);
      return -1;
    };
    for (const auto& n : root.child("ModelStructure").children()) {
      const std::string name = n.name();
      if (name == "ContinuousStateDerivative") {
        const int derivative = index_of_reference(n.attribute("valueReference").as_llong(-1));
        md.state_variables.push_back(
            derivative >= 0 ? index_of_reference(derivative_of[static_cast<std::size_t>(derivative)]) : -1);
      }
      if (name == "EventIndicator") ++md.number_of_event_indicators;
      if (name == "Output") {
        const auto variable = [&](long long vr, const std::string& where) {
          const int i = index_of_reference(vr);
          if (i < 0) fail("<ModelStructure><Output>: " + where + " " + std::to_string(vr) + " is no variable's valueReference");
          return i;
        };
        OutputDependencies o;
        o.variable = variable(n.attribute("valueReference").as_llong(-1), "valueReference");
        if (const auto d = n.attribute("dependencies"))
          o.dependencies = numbers(d.as_string(), [&](long long vr) { return variable(vr, "dependency"); });
        md.output_dependencies.push_back(std::move(o));
      }
    }
    md.number_of_continuous_states = static_cast<int>(md.state_variables.size());
  }
};

// Line and column (1-based) of a byte offset, for the parser's error position.
std::pair<int, int> line_and_column(std::string_view text, std::ptrdiff_t offset) {
  int line = 1, column = 1;
  for (std::ptrdiff_t i = 0; i < offset && i < static_cast<std::ptrdiff_t>(text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

std::optional<double> optional_number(const pugi::xml_node& n, const char* name) {
  const auto a = n.attribute(name);
  if (!a) return std::nullopt;
  return a.as_double();
}

}  // namespace

ModelDescription parse_model_description(std::string_view xml, const FmuLabel& label) {
  pugi::xml_document doc;
  const auto result = doc.load_buffer(xml.data(), xml.size());
  if (!result) {
    const auto [line, column] = line_and_column(xml, result.offset);
    throw FmuError(label, "modelDescription.xml is not well-formed XML: " + std::string(result.description()) +
                              " at line " + std::to_string(line) + ", column " + std::to_string(column));
  }
  const auto root = doc.child("fmiModelDescription");
  if (!root) {
    const auto first = doc.document_element();
    throw FmuError(label, "modelDescription.xml: the root element is <" + std::string(first.name()) +
                              ">, expected <fmiModelDescription>");
  }
  ModelDescription md;
  md.fmi_version = root.attribute("fmiVersion").as_string();
  if (md.fmi_version == "2.0") {
    md.version = FmiVersion::fmi2;
  } else if (md.fmi_version.starts_with("3.")) {
    md.version = FmiVersion::fmi3;
  } else if (md.fmi_version.starts_with("1.")) {
    throw FmuError(label, "is an FMI " + md.fmi_version +
                              " FMU; FMI 1.0 is not supported (mechsim supports FMI 2.0 and 3.0)");
  } else {
    throw FmuError(label, "modelDescription.xml: fmiVersion '" + md.fmi_version +
                              "' is not supported (mechsim supports FMI 2.0 and 3.0)");
  }
  Parser p{label, md.version};
  md.model_name = root.attribute("modelName").as_string();
  md.instantiation_token =
      root.attribute(md.version == FmiVersion::fmi2 ? "guid" : "instantiationToken").as_string();
  md.generation_tool = root.attribute("generationTool").as_string();
  if (const auto n = root.child("ModelExchange")) md.interfaces.push_back(p.read_interface(n, InterfaceKind::model_exchange));
  if (const auto n = root.child("CoSimulation")) md.interfaces.push_back(p.read_interface(n, InterfaceKind::co_simulation));
  if (md.interfaces.empty())
    p.fail("offers neither <CoSimulation> nor <ModelExchange> (mechsim imports these two interfaces)");
  p.read_units(root, md);
  if (md.version == FmiVersion::fmi2)
    p.read_variables_fmi2(root, md);
  else
    p.read_variables_fmi3(root, md);
  if (const auto e = root.child("DefaultExperiment")) {
    md.default_start_time = optional_number(e, "startTime");
    md.default_stop_time = optional_number(e, "stopTime");
    md.default_tolerance = optional_number(e, "tolerance");
    md.default_step_size = optional_number(e, "stepSize");
  }
  return md;
}

}  // namespace mechsim::fmi
