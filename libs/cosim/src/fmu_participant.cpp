#include "fmu_participant.h"

#include <filesystem>
#include <map>

#include "mechsim/config/units.h"
#include "mechsim/cosim/fmu_probe.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/fmi/instantiation.h"
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

// `unpack_limits: {size_mb, ratio}` beside the FMU's file: raises the archive limits (archive.h).
fmi::ArchiveLimits read_unpack_limits(const config::ConfigNode& f) {
  fmi::ArchiveLimits limits;
  const auto l = f.optional_child("unpack_limits");
  if (!l) return limits;
  if (!l->is_map()) l->fail("expected {size_mb: N, ratio: R}: the FMU's unpacked size in MiB and unpacked bytes per archive byte");
  l->allow_only({"size_mb", "ratio"});
  const auto positive = [&](const char* key) {
    const double v = l->number(key);
    if (!(v > 0)) l->child(key).fail("expected a number > 0");
    return v;
  };
  if (l->has("size_mb")) limits.max_unpacked_bytes = static_cast<std::uint64_t>(positive("size_mb") * 1024 * 1024);
  if (l->has("ratio")) limits.max_ratio = positive("ratio");
  return limits;
}

// What a scene says about an FMU, in either form: the map `fmu: {file, interface, step,
// parameters}` (file_key "file") or a participant of type fmu (file_key "fmu").
struct FmuSettings {
  std::shared_ptr<const fmi::FmuArchive> archive;
  std::string file;
  fmi::InterfaceKind kind = fmi::InterfaceKind::co_simulation;
  std::map<std::string, double> parameters;
  double step = 0.0;  // co-simulation step, s
  std::string key;    // the map's key path
};

FmuSettings read_fmu_settings(const config::Scene& scene, const config::ParticipantSpec& spec, const config::ConfigNode& f,
                              const std::string& file_key) {
  FmuSettings out;
  out.key = f.path();
  // The file, relative to the scene file's folder.
  fs::path file = f.string(file_key);
  if (file.is_relative()) file = fs::path(scene.file).parent_path() / file;
  out.file = file.string();
  out.kind = f.has("interface") && f.choice("interface", {"co-simulation", "model-exchange"}) == "model-exchange"
                 ? fmi::InterfaceKind::model_exchange
                 : fmi::InterfaceKind::co_simulation;
  try {
    out.archive = std::make_shared<const fmi::FmuArchive>(fmi::FmuLabel{file.string(), spec.name}, read_unpack_limits(f));
    out.archive->check_binary(out.kind);  // the interface and this host's binary, before anything else
  } catch (const fmi::FmuError& e) {
    refuse(scene, out.key + "." + file_key, std::string("expected a usable FMU: ") + e.what());
  }
  const fmi::ModelDescription& md = out.archive->description();
  // A rollback (any participant restarting) restores every node's checkpoint, which holds
  // an FMU's state only when the FMU can get, set and serialize it. (An adaptive macro step
  // redoes no step and lands on a co-simulation FMU's fixed step: it needs neither.)
  if (const std::string missing = fmi::missing_state_capabilities(md, out.kind); !missing.empty() && scene.checkpointing()) {
    std::string restarts = scene.faults.key_path + ".restart";
    if (scene.faults.restart != "on_failure")
      for (const auto& p : scene.participants)
        if (p.restart) {
          restarts = p.key_path + ".restart";
          break;
        }
    refuse(scene, restarts,
           "expected restart: never while participant '" + spec.name + "' is played by an FMU that cannot save its state: " +
               "a rollback restores every node's checkpoint, and the FMU " + out.file + " does not declare " + missing +
               " (its " + std::string(fmi::to_string(out.kind)) + " interface)");
  }
  // Parameters: each a quantity in the FMU variable's unit (a bare number: SI).
  if (auto p = f.optional_child("parameters")) {
    if (!p->is_map()) p->fail("expected a map {FMU parameter: value}");
    for (const std::string& name : p->keys()) {
      const fmi::Variable* v = md.find_variable(name);
      if (v == nullptr || v->causality != fmi::Causality::parameter || v->type == fmi::ValueType::other)
        p->child(name).fail("expected a parameter of the FMU (see `mechsim fmu info " + file.string() + "`)");
      const auto unit = fmu_unit(md, v->unit);
      if (!unit) p->child(name).fail("expected a parameter in a unit mechsim reads; the FMU's is '" + v->unit + "'");
      const double si = p->child(name).as_quantity(unit->dimension);
      out.parameters[name] = (si - unit->offset) / unit->factor;
    }
  }
  out.step = f.has("step") ? f.positive_quantity("step", config::dim::time) : scene.time.step;
  return out;
}

std::unique_ptr<models::Block> make_block(const config::Scene& scene, const FmuSettings& settings) {
  try {
    if (settings.kind == fmi::InterfaceKind::model_exchange)
      return std::make_unique<fmi::ModelExchangeBlock>(settings.archive, settings.parameters, scene.time.start, scene.time.end);
    return std::make_unique<fmi::CoSimulationBlock>(settings.archive, settings.parameters, scene.time.start, scene.time.end,
                                                    settings.step);
  } catch (const fmi::FmuError& e) {
    refuse(scene, settings.key, std::string("expected an FMU that initializes: ") + e.what());
  }
}

// An FMU port's unit as the unit check sees it ("1" or none: dimensionless).
std::optional<FmuUnit> port_unit(const FmuParticipant* fmu, const std::string& unit) {
  if (fmu) return fmu_unit(fmu->archive->description(), unit);
  try {
    return FmuUnit{native_dimension(unit), 1.0, 0.0};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

void check_connection_units(const config::Scene& scene, const std::string& key_path, const std::string& from_port,
                            const std::string& from_unit, const FmuParticipant* from_fmu, const std::string& to_port,
                            const std::string& to_unit, const FmuParticipant* to_fmu) {
  const auto a = port_unit(from_fmu, from_unit), b = port_unit(to_fmu, to_unit);
  const auto shown = [](const std::string& u) { return u.empty() ? std::string("no unit") : "'" + u + "'"; };
  const std::string both = from_port + " is in " + shown(from_unit) + ", " + to_port + " in " + shown(to_unit);
  if (!a || !b)
    refuse(scene, key_path, "expected units mechsim can compare (" + both + "; " + (a ? to_port : from_port) +
                                "'s has no definition mechsim reads)");
  if (!(a->dimension == b->dimension) || a->factor != b->factor || a->offset != b->offset)
    refuse(scene, key_path, "expected the same unit on both sides of the connection: " + both);
}

BuiltFmuParticipant make_fmu_participant(const config::Scene& scene, const config::ParticipantSpec& spec,
                                         const config::ConfigNode* coupling) {
  const bool beside = spec.fmu_participant.has_value();
  const config::ConfigNode& f = beside ? *spec.fmu_participant : *spec.fmu;
  if (!beside) {
    if (!f.is_map()) f.fail("expected {file: PATH, interface: co-simulation|model-exchange, step, parameters}");
    f.allow_only({"file", "interface", "step", "parameters", "unpack_limits"});
  }
  if (coupling)
    refuse(scene, spec.key_path, "expected no coupling element at an FMU participant (its ports are joined port by port)");
  FmuSettings settings = read_fmu_settings(scene, spec, f, beside ? "fmu" : "file");
  BuiltFmuParticipant built;
  built.block = make_block(scene, settings);
  auto participant = std::make_shared<FmuParticipant>();
  participant->archive = settings.archive;
  participant->file = settings.file;
  // The topic's fields: the block's outputs (the FMU's exchanged outputs, in description order).
  const fmi::ModelDescription& md = settings.archive->description();
  std::vector<transport::FieldInfo> fields;
  for (const auto& out : built.block->outputs()) {
    const fmi::Variable* v = md.find_variable(out.name);
    const transport::FieldKind kind = v && v->type == fmi::ValueType::integer   ? transport::FieldKind::i32
                                      : v && v->type == fmi::ValueType::boolean ? transport::FieldKind::boolean
                                                                                : transport::FieldKind::f64;
    transport::FieldInfo field{out.name, kind};
    field.unit = out.unit;
    fields.push_back(std::move(field));
  }
  try {
    participant->topic_type = transport::fmu_topic_type(std::move(fields));
  } catch (const std::invalid_argument& e) {
    refuse(scene, spec.key_path, std::string("expected an FMU whose outputs fit on its topic: ") + e.what());
  }
  participant->node_type = NodeType{kFmuNodeType,
                                    "an FMU with ports of its own; publishes FmuOutputs",
                                    &participant->topic_type,
                                    "outputs",
                                    [](const config::ConfigNode&, const config::ConfigNode*) -> std::unique_ptr<models::Block> {
                                      throw std::logic_error("an FMU participant's block is made by make_fmu_participant");
                                    },
                                    {}};
  built.participant = std::move(participant);
  return built;
}

std::unique_ptr<models::Block> make_fmu_block(const config::Scene& scene, const config::ParticipantSpec& spec,
                                              const NodeType& type, const models::Block& native,
                                              const config::ConfigNode* coupling) {
  const config::ConfigNode& f = *spec.fmu;
  const std::string key = f.path();
  if (!f.is_map()) f.fail("expected {file: PATH, interface: co-simulation|model-exchange, step, parameters}");
  f.allow_only({"file", "interface", "step", "parameters", "unpack_limits"});
  if (coupling)
    refuse(scene, key, "expected no coupling element at a participant played by an FMU (the cut's spring-damper "
                       "is evaluated by the native blocks)");
  const FmuSettings settings = read_fmu_settings(scene, spec, f, "file");
  const fmi::ModelDescription& md = settings.archive->description();
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

  return make_block(scene, settings);
}

}  // namespace mechsim::cosim

namespace mechsim::cosim {

namespace {

// The FMU block of a planned node, as either kind (nullptr: a native block).
template <typename F>
void with_fmu_block(const models::Block* block, F&& f) {
  if (const auto* cs = dynamic_cast<const fmi::CoSimulationBlock*>(block)) f(*cs);
  if (const auto* me = dynamic_cast<const fmi::ModelExchangeBlock*>(block)) f(*me);
}

}  // namespace

std::vector<PlannedFmu> planned_fmus(const ScenePlan& plan) {
  std::vector<PlannedFmu> out;
  for (const auto& node : plan.nodes())
    with_fmu_block(node.block.get(), [&](const auto& b) { out.push_back({node.name(), b.archive().label().file}); });
  return out;
}

void defer_fmu_instantiation() { fmi::set_block_instantiation(fmi::Instantiation::at_first_use); }

void instantiate_fmu(const ScenePlan& plan, const std::string& participant) {
  const PlannedNode& node = plan.node(participant);
  const std::string key = node.spec->key_path + ".fmu";
  with_fmu_block(node.block.get(), [&](const auto& b) {
    try {
      b.instantiate_now();
    } catch (const fmi::FmuError& e) {
      refuse(plan.scene(), key, std::string("expected an FMU that initializes: ") + e.what());
    }
  });
}

}  // namespace mechsim::cosim
