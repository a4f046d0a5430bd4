#include "mechsim/fmi_export/exported_participant.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "exact_decimal.h"
#include "mechsim/catalog/catalog.h"

namespace mechsim::fmi_export {

namespace {

// The SI name of a dimension: a familiar one where there is one, else its base units.
std::string si_unit_name(const config::Dimension& d) {
  static const char* const kNames[] = {"1",     "m",       "kg",    "s",         "A",       "rad",   "rad/s",
                                       "rad/s^2", "m/s",   "m/s^2", "N",         "N m",     "N/m",   "N s/m",
                                       "N m/rad", "N m s/rad", "kg m^2", "Pa",   "W",       "J",     "V",
                                       "ohm",   "H",       "1/s",   "V s/rad",   "N m/A",   "kg/m^3"};
  for (const char* name : kNames) {
    const config::Quantity q = config::parse_quantity(std::string("1 ") + name);
    if (q.dimension == d && q.value_si == 1.0) return name;
  }
  return config::base_units(d);
}

// Every numeric leaf under `node`, depth first in document order, with its dotted path
// ("setpoint.distance", "law[2].lift"). Strings, booleans and choices are not parameters.
void collect_numeric_leaves(const YAML::Node& node, const std::string& path,
                            std::vector<std::pair<std::string, config::Quantity>>& out) {
  if (node.IsMap()) {
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      collect_numeric_leaves(kv.second, path.empty() ? key : path + "." + key, out);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) collect_numeric_leaves(node[i], path + "[" + std::to_string(i) + "]", out);
  } else if (node.IsScalar()) {
    try {
      out.emplace_back(path, config::parse_quantity(node.Scalar()));
    } catch (const config::UnitError&) {
      // not a number: a choice ("type: step") or a flag; stays as the scene wrote it
    }
  }
}

// The scene's solver spec as the integrator's options, as cosim::solver_options does for a
// node; that function lives with the node stepper, whose object file would pull the
// stepping and DDS layers into the FMU binary.
solve::SolverOptions integrator_options(const config::SolverSpec& spec) {
  solve::SolverOptions o;
  const auto& names = config::solver_method_names();  // in the order of solve::Method
  o.method = static_cast<solve::Method>(std::find(names.begin(), names.end(), spec.method) - names.begin());
  o.rtol = spec.rtol;
  o.atol = spec.atol;
  return o;
}

}  // namespace

std::string write_export_config(const ExportConfig& c) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "mechsim_fmu_export" << YAML::Value << 1;
  out << YAML::Key << "participant" << YAML::Value << c.participant;
  out << YAML::Key << "type" << YAML::Value << c.type;
  out << YAML::Key << "scene" << YAML::Value << c.scene;
  out << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "method" << YAML::Value << c.solver.method;
  out << YAML::Key << "rtol" << YAML::Value << exact(c.solver.rtol);
  out << YAML::Key << "atol" << YAML::Value << exact(c.solver.atol);
  out << YAML::EndMap;
  out << YAML::Key << "params" << YAML::Value << YAML::Load(c.params.to_yaml());
  if (c.coupling) out << YAML::Key << "coupling" << YAML::Value << YAML::Load(c.coupling->to_yaml());
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

ExportConfig read_export_config(const std::string& text, const std::string& file) {
  const config::ConfigNode root = config::ConfigNode::from_string(text, file);
  root.allow_only({"mechsim_fmu_export", "participant", "type", "scene", "solver", "params", "coupling"});
  if (root.integer("mechsim_fmu_export") != 1) root.fail("expected mechsim_fmu_export: 1 (the layout this binary reads)");
  ExportConfig c;
  c.participant = root.string("participant");
  c.type = root.string("type");
  c.scene = root.string_or("scene", "");
  const config::ConfigNode solver = root.child("solver");
  c.solver.method = solver.choice("method", config::solver_method_names());
  c.solver.rtol = solver.number("rtol");
  c.solver.atol = solver.number("atol");
  c.solver.rtol_written = c.solver.atol_written = true;
  c.params = root.has("params") ? root.child("params") : config::ConfigNode::from_string("{}", file);
  if (root.has("coupling")) c.coupling = root.child("coupling");
  return c;
}

std::vector<UnitDefinition> unit_definitions(const std::vector<ExportedVariable>& variables) {
  std::vector<UnitDefinition> units;
  for (const auto& v : variables) {
    if (v.unit.empty() || std::any_of(units.begin(), units.end(), [&](const auto& u) { return u.name == v.unit; })) continue;
    try {
      const config::Quantity q = config::parse_quantity("1 " + v.unit);
      units.push_back({v.unit, q.dimension, q.value_si});
    } catch (const config::UnitError&) {
      units.push_back({v.unit, {}, std::numeric_limits<double>::quiet_NaN()});  // named only
    }
  }
  return units;
}

ExportedParticipant::ExportedParticipant(ExportConfig config) : config_(std::move(config)) {
  if (cosim::find_node_type(config_.type) == nullptr)
    throw std::invalid_argument("participant '" + config_.participant + "': unknown node type '" + config_.type + "'");
  rebuild_block();
  const models::Block& b = *block_;
  for (int i = 0; i < b.num_inputs(); ++i) {
    const auto& p = b.inputs()[i];
    // FMI names are unique; a block may read and publish a quantity of the same name (the
    // follower's cam `acceleration` in, its own out): the input is then `<name>_in`.
    const bool clash = b.output_index(p.name) >= 0;
    variables_.push_back({clash ? p.name + "_in" : p.name, VariableKind::input, i, p.unit, p.default_value,
                          std::string(p.required ? "required input (connect it)" : "input") +
                              (clash ? ", the block's input '" + p.name + "'" : "")});
  }
  for (int i = 0; i < b.num_outputs(); ++i)
    variables_.push_back({b.outputs()[i].name, VariableKind::output, i, b.outputs()[i].unit, 0.0, "output"});
  std::vector<std::pair<std::string, config::Quantity>> leaves;
  collect_numeric_leaves(config_.params.yaml(), "", leaves);
  for (const auto& [path, q] : leaves) {
    // A port and a parameter of the same name cannot both be variables: the port wins.
    if (std::any_of(variables_.begin(), variables_.end(), [&](const auto& v) { return v.name == path; })) continue;
    const int index = static_cast<int>(parameters_.size());
    variables_.push_back({path, VariableKind::parameter, index, q.has_unit ? si_unit_name(q.dimension) : "", q.value_si,
                          "params." + path + " of the scene (SI)"});
    parameter_paths_.push_back(path);
    parameters_.push_back(q.value_si);
  }
  u_ = b.default_inputs();
  y_.assign(b.num_outputs(), 0.0);
}

ExportedParticipant::~ExportedParticipant() = default;

void ExportedParticipant::rebuild_block() {
  // The integrator refers to the block: a new block only before initialization ends.
  block_ = cosim::find_node_type(config_.type)->make_block(config_.params, config_.coupling ? &*config_.coupling : nullptr);
  x0_.assign(block_->num_states(), 0.0);
  block_->initial_state(t_, x0_);
  parameters_changed_ = false;
  outputs_stale_ = true;
}

const ExportedVariable* ExportedParticipant::variable(unsigned vr) const {
  if (vr == kTimeValueReference || vr > variables_.size()) return nullptr;
  return &variables_[vr - 1];
}

void ExportedParticipant::set_real(unsigned vr, double value) {
  if (vr == kTimeValueReference) throw std::invalid_argument("time (value reference 0) cannot be set");
  const ExportedVariable* v = variable(vr);
  if (v == nullptr) throw std::invalid_argument("no variable has value reference " + std::to_string(vr));
  switch (v->kind) {
    case VariableKind::input:
      u_[v->index] = value;
      outputs_stale_ = true;
      return;
    case VariableKind::output:
      throw std::invalid_argument("'" + v->name + "' is an output; it cannot be set");
    case VariableKind::parameter:
      if (integrator_) throw std::invalid_argument("parameter '" + v->name + "' can be set only before initialization ends");
      parameters_[v->index] = value;
      config_.params.set_override(parameter_paths_[v->index], exact(value));
      parameters_changed_ = true;
      return;
  }
}

double ExportedParticipant::get_real(unsigned vr) {
  if (vr == kTimeValueReference) return t_;
  const ExportedVariable* v = variable(vr);
  if (v == nullptr) throw std::invalid_argument("no variable has value reference " + std::to_string(vr));
  switch (v->kind) {
    case VariableKind::input: return u_[v->index];
    case VariableKind::parameter: return parameters_[v->index];
    case VariableKind::output: break;
  }
  if (parameters_changed_) rebuild_block();
  if (outputs_stale_) refresh_outputs();
  return y_[v->index];
}

void ExportedParticipant::refresh_outputs() {
  block_->calc_outputs(t_, integrator_ ? integrator_->state() : std::span<const double>(x0_), u_, y_);
  outputs_stale_ = false;
}

void ExportedParticipant::enter_initialization(double start_time, double stop_time) {
  t_ = start_time;
  stop_time_ = stop_time;
  initializing_ = true;
  parameters_changed_ = true;  // the initial state may depend on t0
}

void ExportedParticipant::exit_initialization() {
  if (!initializing_) throw std::logic_error("exit_initialization before enter_initialization");
  if (parameters_changed_) rebuild_block();
  integrator_ = std::make_unique<solve::BlockIntegrator>(*block_, integrator_options(config_.solver), t_, x0_);
  // A sampled block takes its t0 sample now, as the node does (NodeStepper::initialise).
  if (block_->sample_time() > 0)
    integrator_->advance_to(t_, [this](double, std::span<double> u) { std::copy(u_.begin(), u_.end(), u.begin()); });
  if (std::isfinite(stop_time_)) scheduled_ = block_->scheduled_events(t_, stop_time_);
  initializing_ = false;
  outputs_stale_ = true;
}

void ExportedParticipant::do_step(double t, double h) {
  if (!integrator_) throw std::logic_error("do_step before initialization ended");
  if (!(h > 0)) throw std::invalid_argument("the communication step must be > 0 s, got " + exact(h) + " s");
  // The grid's instants are computed, not accumulated, by the importer: allow rounding.
  if (std::abs(t - t_) > 1e-9 * std::max(1.0, std::abs(t)))
    throw std::invalid_argument("do_step from t = " + exact(t) + " s, but the FMU is at t = " + exact(t_) +
                                " s (it cannot go back: no FMU state)");
  const double t_end = t + h;
  const auto held = [this](double, std::span<double> u) { std::copy(u_.begin(), u_.end(), u.begin()); };
  if (!std::isfinite(stop_time_)) scheduled_ = block_->scheduled_events(t, t_end);
  integrator_->mark_discontinuity();  // the held inputs start afresh each step
  for (const double event : scheduled_) {
    if (event <= t) continue;
    if (event >= t_end) break;
    integrator_->advance_to(event, held);
    integrator_->mark_discontinuity();
  }
  integrator_->advance_to(t_end, held);
  t_ = t_end;
  outputs_stale_ = true;
}

ExportedParticipant::State ExportedParticipant::state() const {
  if (!integrator_) throw std::logic_error("the FMU state is there only after initialization ended");
  const auto x = integrator_->state();
  return {t_, std::vector<double>(x.begin(), x.end()), block_->save_discrete_state(), u_};
}

void ExportedParticipant::set_state(const State& s) {
  if (!integrator_) throw std::logic_error("an FMU state can be set only after initialization ended");
  if (s.x.size() != x0_.size() || s.u.size() != u_.size())
    throw std::invalid_argument("the FMU state is not one of this participant (" + std::to_string(s.x.size()) +
                                " states, " + std::to_string(s.u.size()) + " inputs)");
  block_->restore_discrete_state(s.discrete);
  integrator_->reset_state(s.t, s.x);
  u_ = s.u;
  t_ = s.t;
  outputs_stale_ = true;
}

std::vector<unsigned char> ExportedParticipant::serialize(const State& s) {
  std::vector<double> flat{s.t};
  for (const auto* part : {&s.x, &s.discrete, &s.u}) {
    flat.push_back(static_cast<double>(part->size()));
    flat.insert(flat.end(), part->begin(), part->end());
  }
  std::vector<unsigned char> bytes(flat.size() * sizeof(double));
  std::memcpy(bytes.data(), flat.data(), bytes.size());
  return bytes;
}

ExportedParticipant::State ExportedParticipant::deserialize(const unsigned char* bytes, std::size_t size) {
  if (size % sizeof(double) != 0 || size < 4 * sizeof(double))
    throw std::invalid_argument("a serialized FMU state of " + std::to_string(size) + " bytes is not one of mechsim's");
  std::vector<double> flat(size / sizeof(double));
  std::memcpy(flat.data(), bytes, size);
  State s;
  s.t = flat[0];
  std::size_t at = 1;
  for (auto* part : {&s.x, &s.discrete, &s.u}) {
    if (at >= flat.size()) throw std::invalid_argument("a serialized FMU state ends early");
    const double n = flat[at++];
    if (!(n >= 0) || n > static_cast<double>(flat.size() - at)) throw std::invalid_argument("a serialized FMU state is damaged");
    part->assign(flat.begin() + static_cast<std::ptrdiff_t>(at), flat.begin() + static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(n)));
    at += static_cast<std::size_t>(n);
  }
  if (at != flat.size()) throw std::invalid_argument("a serialized FMU state has bytes left over");
  return s;
}

}  // namespace mechsim::fmi_export
