#include "fmu_participant.h"

#include <filesystem>
#include <map>

#include "mechsim/config/units.h"
#include "mechsim/fmi/co_simulation_block.h"
#include "mechsim/fmi/model_exchange_block.h"

namespace mechsim::cosim {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse(const config::Scene& scene, const std::string& key_path, const std::string& expected) {
  throw config::ConfigError(scene.file, key_path, expected);
}

// The dimension and SI factor/offset of an FMU unit: from its <UnitDefinitions> entry, else
// its name read by mechsim's unit parser. nullopt when neither says (or the unit has
// kelvin, mole or candela exponents, which mechsim's dimensions do not carry).
struct FmuUnit {
  config::Dimension dimension;
  double factor = 1.0, offset = 0.0;
};
std::optional<FmuUnit> fmu_unit(const fmi::ModelDescription& md, const std::string& name) {
  if (name.empty() || name == "1") return FmuUnit{};
  if (const fmi::UnitDefinition* u = md.find_unit(name)) {
    if (u->K != 0 || u->mol != 0 || u->cd != 0) return std::nullopt;
    FmuUnit out;
    out.dimension.exp = {u->m, u->kg, u->s, u->A, u->rad};
    out.factor = u->factor;
    out.offset = u->offset;
    return out;
  }
  try {
    const config::Quantity q = config::parse_quantity("1 " + name);
    return FmuUnit{q.dimension, q.value_si, 0.0};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The native port's unit as a dimension ("1": dimensionless).
config::Dimension native_dimension(const std::string& unit) {
  if (unit.empty() || unit == "1") return config::dim::dimensionless;
  return config::parse_quantity("1 " + unit).dimension;
}

// Refuses an FMU port whose unit is not the native port's (by dimension and SI scale).
void check_unit(const config::Scene& scene, const std::string& key_path, const fmi::ModelDescription& md,
                const fmi::Variable& v, const std::string& native_unit, const std::string& port_kind) {
  const auto unit = fmu_unit(md, v.unit);
  const std::string shown = v.unit.empty() ? "none" : "'" + v.unit + "'";
  if (!unit)
    refuse(scene, key_path, "expected FMU " + port_kind + " '" + v.name + "' in a unit mechsim can compare with '" +
                                native_unit + "'; its unit " + shown + " has no definition mechsim reads");
  if (!(unit->dimension == native_dimension(native_unit)) || unit->factor != 1.0 || unit->offset != 0.0)
    refuse(scene, key_path, "expected FMU " + port_kind + " '" + v.name + "' in the native port's unit '" +
                                native_unit + "', got " + shown);
}

}  // namespace

std::unique_ptr<models::Block> make_fmu_block(const config::Scene& scene, const config::ParticipantSpec& spec,
                                              const NodeType& type, const models::Block& native,
                                              const config::ConfigNode* coupling) {
  const config::ConfigNode& f = *spec.fmu;
  const std::string key = f.path();
  if (!f.is_map()) f.fail("expected {file: PATH, interface: co-simulation|model-exchange, step, parameters}");
  f.allow_only({"file", "interface", "step", "parameters"});
  if (coupling)
    refuse(scene, key, "expected no coupling element at a participant played by an FMU (the cut's spring-damper "
                       "is evaluated by the native blocks)");
  // The file, relative to the scene file's folder.
  fs::path file = f.string("file");
  if (file.is_relative()) file = fs::path(scene.file).parent_path() / file;
  const fmi::InterfaceKind kind = f.has("interface") && f.choice("interface", {"co-simulation", "model-exchange"}) ==
                                                            "model-exchange"
                                      ? fmi::InterfaceKind::model_exchange
                                      : fmi::InterfaceKind::co_simulation;
  std::shared_ptr<const fmi::FmuArchive> archive;
  try {
    archive = std::make_shared<const fmi::FmuArchive>(fmi::FmuLabel{file.string(), spec.name});
    archive->binary_path(kind);  // the interface and this host's binary, before anything else
  } catch (const fmi::FmuError& e) {
    refuse(scene, key + ".file", std::string("expected a usable FMU: ") + e.what());
  }
  const fmi::ModelDescription& md = archive->description();
  // A rollback (any participant restarting) restores every node's checkpoint, which holds
  // an FMU's state only when the FMU can get, set and serialize it. (An adaptive macro step
  // redoes no step and lands on a co-simulation FMU's fixed step: it needs neither.)
  if (const std::string missing = fmi::missing_state_capabilities(md, kind); !missing.empty() && scene.checkpointing()) {
    std::string restarts = scene.faults.key_path + ".restart";
    if (scene.faults.restart != "on_failure")
      for (const auto& p : scene.participants)
        if (p.restart) {
          restarts = p.key_path + ".restart";
          break;
        }
    refuse(scene, restarts,
           "expected restart: never while participant '" + spec.name + "' is played by an FMU that cannot save its state: " +
               "a rollback restores every node's checkpoint, and the FMU " + file.string() + " does not declare " +
               missing + " (its " + std::string(fmi::to_string(kind)) + " interface)");
  }

  // Parameters: each a quantity in the FMU variable's unit (a bare number: SI).
  std::map<std::string, double> parameters;
  if (auto p = f.optional_child("parameters")) {
    if (!p->is_map()) p->fail("expected a map {FMU parameter: value}");
    for (const std::string& name : p->keys()) {
      const fmi::Variable* v = md.find_variable(name);
      if (v == nullptr || v->causality != fmi::Causality::parameter || v->type == fmi::ValueType::other)
        p->child(name).fail("expected a parameter of the FMU (see `mechsim fmu info " + file.string() + "`)");
      const auto unit = fmu_unit(md, v->unit);
      if (!unit) p->child(name).fail("expected a parameter in a unit mechsim reads; the FMU's is '" + v->unit + "'");
      const double si = p->child(name).as_quantity(unit->dimension);
      parameters[name] = (si - unit->offset) / unit->factor;
    }
  }

  // The native block's ports, by name and unit: outputs its topic publishes, inputs it requires.
  const auto exchanged = [&](const std::string& name, fmi::Causality causality) -> const fmi::Variable* {
    const fmi::Variable* v = md.find_variable(name);
    return v && v->causality == causality && v->type != fmi::ValueType::other ? v : nullptr;
  };
  for (const auto& field : type.publishes->fields) {
    const int o = native.output_index(field.name);
    if (o < 0) continue;  // not computed by this configuration
    const fmi::Variable* v = exchanged(field.name, fmi::Causality::output);
    if (!v)
      refuse(scene, key + ".file", "expected the FMU to have an output '" + field.name + "' (published on " +
                                       type.publishes->idl_name + " by a " + type.name + ")");
    check_unit(scene, key + ".file", md, *v, native.outputs()[static_cast<std::size_t>(o)].unit, "output");
  }
  for (const auto& in : native.inputs()) {
    const fmi::Variable* v = exchanged(in.name, fmi::Causality::input);
    if (!v) {
      if (in.required)
        refuse(scene, key + ".file", "expected the FMU to have an input '" + in.name + "' (a " + type.name +
                                         " reads it)");
      continue;
    }
    check_unit(scene, key + ".file", md, *v, in.unit, "input");
  }

  try {
    if (kind == fmi::InterfaceKind::model_exchange)
      return std::make_unique<fmi::ModelExchangeBlock>(archive, parameters, scene.time.start, scene.time.end);
    const double step = f.has("step") ? f.positive_quantity("step", config::dim::time) : scene.time.step;
    return std::make_unique<fmi::CoSimulationBlock>(archive, parameters, scene.time.start, scene.time.end, step);
  } catch (const fmi::FmuError& e) {
    refuse(scene, key, std::string("expected an FMU that initializes: ") + e.what());
  }
}

}  // namespace mechsim::cosim
