#include "mechsim/cosim/scene_plan.h"

#include "fmu_participant.h"

#include "mechsim/fmi/co_simulation_block.h"

#include "mechsim/config/units.h"
#include "coupling/cut_plan.h"
#include "mechsim/catalog/coupling/coupling_spec.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>

namespace mechsim::cosim {

namespace {

[[noreturn]] void refuse(const config::Scene& scene, const std::string& key_path, const std::string& expected) {
  throw config::ConfigError(scene.file, key_path, expected);
}

// Depth-first search for a cycle in a directed graph given as adjacency lists; returns the
// cycle as a list of vertices (empty when acyclic).
std::vector<int> find_cycle(const std::vector<std::vector<int>>& adjacent) {
  const int n = static_cast<int>(adjacent.size());
  std::vector<int> color(n, 0), parent(n, -1);
  std::vector<int> cycle;
  std::function<bool(int)> visit = [&](int v) {
    color[v] = 1;
    for (int w : adjacent[v]) {
      if (color[w] == 1) {
        for (int x = v; x != w; x = parent[x]) cycle.insert(cycle.begin(), x);
        cycle.insert(cycle.begin(), w);
        return true;
      }
      if (color[w] == 0) {
        parent[w] = v;
        if (visit(w)) return true;
      }
    }
    color[v] = 2;
    return false;
  };
  for (int v = 0; v < n; ++v)
    if (color[v] == 0 && visit(v)) return cycle;
  return {};
}

// A port-level connection `from: P.field, to: Q.input`: P's topic field feeds Q's block
// input, each named by the scene, in the same unit. Connections between the same two
// participants share one edge (one reader of P's topic), so they must agree on order and
// reconstruction.
void plan_port_connection(const config::Scene& scene, const config::ConnectionSpec& c, PlannedNode& from, PlannedNode& to) {
  const auto names = [](const auto& list) {
    std::string known;
    for (const auto& item : list) known += (known.empty() ? "" : ", ") + item.name;
    return known;
  };
  const transport::TopicType& type = *from.type->publishes;
  const int f = type.field_index(c.from_field);
  if (f < 0 || from.published_outputs[static_cast<std::size_t>(f)] < 0)
    refuse(scene, c.key_path + ".from", "expected an output '" + c.from + "' publishes (" + names(type.fields) + "), got '" +
                                            c.from_field + "'");
  const int i = to.block->input_index(c.to_input);
  if (i < 0)
    refuse(scene, c.key_path + ".to", "expected an input of '" + c.to + "' (" + names(to.block->inputs()) + "), got '" +
                                          c.to_input + "'");
  const auto& out = from.block->outputs()[static_cast<std::size_t>(from.published_outputs[static_cast<std::size_t>(f)])];
  check_connection_units(scene, c.key_path, c.from + "." + c.from_field, out.unit, from.fmu.get(), c.to + "." + c.to_input,
                         to.block->inputs()[static_cast<std::size_t>(i)].unit, to.fmu.get());
  if (c.initial) refuse(scene, c.key_path + ".initial", "expected no initial values on a port-level connection");
  for (const auto& other : to.inputs)
    for (const auto& [of, oi] : other.field_to_input)
      if (oi == i)
        refuse(scene, c.key_path, "expected each input of '" + c.to + "' fed once: input '" + c.to_input +
                                      "' is already fed by '" + other.from + "'");
  for (auto& edge : to.inputs)
    if (edge.from == c.from) {
      if (edge.order != c.order || edge.reconstruction != c.reconstruction)
        refuse(scene, c.key_path, "expected the same order and reconstruction on every connection from '" + c.from + "' to '" +
                                      c.to + "' (they share one reader of " + from.topic + ")");
      edge.field_to_input.emplace_back(f, i);
      return;
    }
  InboundEdge edge;
  edge.from = c.from;
  edge.topic = from.topic;
  edge.type = &type;
  edge.order = c.order;
  edge.reconstruction = c.reconstruction;
  edge.field_to_input.emplace_back(f, i);
  to.inputs.push_back(std::move(edge));
  ++from.subscriber_count;
}

// The times in (t0, t_end) at which a shaft turning as `rotation` brings the angle to
// `event` (rad in [0, 2 pi)), each moved to the first double at which `reached` says the
// block sees the angle on the event's far side (a few ulps at most).
std::vector<double> times_of_angle(const models::Block::UniformRotation& rotation, double event, double t0, double t_end,
                                   const std::function<bool(double theta)>& reached, std::size_t at_most) {
  std::vector<double> times;
  if (!(rotation.speed > 0)) return times;  // a shaft at rest or turning back: not planned
  const double two_pi = 2.0 * std::numbers::pi;
  const double first_turn = std::floor((rotation.angle(t0) - event) / two_pi);
  for (double n = first_turn; times.size() <= at_most; n += 1.0) {
    double t = (event + n * two_pi - rotation.angle0) / rotation.speed;
    if (t >= t_end) break;
    const double up = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 64 && !reached(rotation.angle(t)); ++i) t = std::nextafter(t, up);
    for (int i = 0; i < 64 && reached(rotation.angle(std::nextafter(t, -up))); ++i) t = std::nextafter(t, -up);
    if (t > t0 && t < t_end) times.push_back(t);
  }
  return times;
}

}  // namespace

// Each event costs a step of its own; far more than any mechanism schedules means a scene
// written wrong (a cam speed in rad/s where rpm was meant, an end time in hours).
constexpr std::size_t kMaxScheduledEvents = 100'000;

void ScenePlan::land_on_scheduled_events() {
  const config::TimeSpec& time = scene_->time;
  const auto too_many = [&](const PlannedNode& node) {
    if (scheduled_events_.size() > kMaxScheduledEvents)
      refuse(*scene_, node.spec->key_path + ".params",
             "at most " + std::to_string(kMaxScheduledEvents) + " discontinuities scheduled in the run (each lands a step), "
             "got more; check the speeds and the time section");
  };
  for (auto& node : nodes_) {
    for (double t : node.block->scheduled_events(time.start, time.end)) scheduled_events_.push_back({node.name(), t});
    too_many(node);
    // An adaptive step also lands on a uniformly turning shaft's law joints (Block::angle_law_changes),
    // and on those of a shaft whose speed varies where the node predicts them at run time.
    const auto rotation = node.block->uniform_rotation();
    const std::vector<double> joints = time.adaptive ? node.block->angle_law_changes() : std::vector<double>{};
    if (!rotation && !joints.empty() && node.block->output_index("angle") >= 0) node.run_time_angle_events.push_back({true, joints});
    if (rotation) {
      const double two_pi = 2.0 * std::numbers::pi;
      for (double angle : joints) {
        const auto past = [&](double theta) { return theta - two_pi * std::floor(theta / two_pi) >= angle; };
        for (double t : times_of_angle(*rotation, angle, time.start, time.end, past, kMaxScheduledEvents))
          scheduled_events_.push_back({node.name(), t});
        too_many(node);
      }
    }
    // Angle events, where the block's `angle` input is a uniformly turning shaft's angle.
    const std::vector<double> angles = node.block->angle_events();
    const int angle_input = node.block->input_index("angle");
    if (angles.empty() || angle_input < 0) continue;
    for (const auto& edge : node.inputs)
      for (const auto& [field, input] : edge.field_to_input) {
        if (input != angle_input || edge.type->fields[static_cast<std::size_t>(field)].name != "angle") continue;
        const auto rotation = this->node(edge.from).block->uniform_rotation();
        if (!rotation) {
          if (time.adaptive) node.run_time_angle_events.push_back({false, angles});
          continue;
        }
        for (double angle : angles) {
          for (double t : times_of_angle(*rotation, angle, time.start, time.end,
                                         [&](double theta) { return node.block->angle_event_reached(theta, angle); },
                                         kMaxScheduledEvents))
            scheduled_events_.push_back({node.name(), t});
          too_many(node);
        }
      }
  }
  std::sort(scheduled_events_.begin(), scheduled_events_.end(),
            [](const ScheduledEvent& a, const ScheduledEvent& b) { return a.t != b.t ? a.t < b.t : a.participant < b.participant; });
  // A jump written as two schedule rows at one time is one event of that participant.
  scheduled_events_.erase(std::unique(scheduled_events_.begin(), scheduled_events_.end(),
                                      [](const ScheduledEvent& a, const ScheduledEvent& b) {
                                        return a.t == b.t && a.participant == b.participant;
                                      }),
                          scheduled_events_.end());
  std::vector<double> times;
  for (const auto& e : scheduled_events_) times.push_back(e.t);
  // Every node plans the same scene, so every node lands on the same events: no message.
  grid_ = time.adaptive ? std::make_shared<const StepGrid>(StepGrid::adaptive(time, times))
                        : std::make_shared<const StepGrid>(StepGrid::landing_on(time, times));
}

std::vector<std::pair<std::string, std::string>> ScenePlan::scaled_quantities() const {
  std::vector<std::pair<std::string, std::string>> out;
  const auto add = [&](const std::string& participant, const std::string& field) {
    if (std::find(out.begin(), out.end(), std::make_pair(participant, field)) == out.end()) out.emplace_back(participant, field);
  };
  for (const auto& node : nodes_) {
    for (const auto& edge : node.inputs)
      for (const auto& [field, input] : edge.field_to_input) add(edge.from, edge.type->fields[static_cast<std::size_t>(field)].name);
    for (const int o : node.watched_outputs)
      if (std::find(node.published_outputs.begin(), node.published_outputs.end(), o) != node.published_outputs.end())
        add(node.name(), node.block->outputs()[static_cast<std::size_t>(o)].name);
  }
  return out;
}

namespace {

// The analyses that read a scene's `design:` section, by the key they read (docs/scenes.md).
// A scene written for one of them may lack what a time run needs (cvt_map.yaml has no drive).
std::string analyses_of(const config::Scene& scene) {
  static const std::pair<const char*, const char*> kAnalyses[] = {
      {"cvt_map", "mechsim cvt-map"}, {"motor", "mechsim motor-bode"}, {"follower", "mechsim cam-design"}};
  std::string commands;
  if (!scene.design || !scene.design->is_map()) return commands;
  for (const auto& [key, command] : kAnalyses)
    if (scene.design->has(key)) commands += std::string(commands.empty() ? "`" : " or `") + command + " " + scene.file + "`";
  return commands;
}

}  // namespace

ScenePlan ScenePlan::build(const config::Scene& scene) {
  try {
    return build_time_run(scene);
  } catch (const config::ConfigError& e) {
    const std::string analyses = analyses_of(scene);
    if (analyses.empty()) throw;
    throw config::ConfigError(e.file(), e.key_path(),
                              e.expected() + " (" + std::filesystem::path(scene.file).filename().string() +
                                  " is a scene for " + analyses + " (its design: section); a time run of it needs this key)",
                              e.line());
  }
}

namespace {

// The element at the cut of any connection to or from a participant (at most one).
const config::ConfigNode* coupling_element_of(const config::Scene& scene, const config::ParticipantSpec& spec) {
  const config::ConfigNode* coupling = nullptr;
  for (const auto& c : scene.connections)
    if ((c.from == spec.name || c.to == spec.name) && c.coupling) {
      if (coupling) refuse(scene, c.key_path + ".coupling", "expected at most one coupling element per participant");
      coupling = &*c.coupling;
    }
  return coupling;
}

// The participant's block: its node type's, an FMU participant's, or an FMU in place of the
// native block (which stays the template of its ports).
void build_block(const config::Scene& scene, const config::ParticipantSpec& spec, PlannedNode& node) {
  const config::ConfigNode* coupling = coupling_element_of(scene, spec);
  // A model's own check of its parameters (libs/models validate(), or parameters outside
  // what the model describes) is the scene's error, named by the participant's params
  // (found by tests/fuzz/scene_fuzz: overlapping follower loads ended the process instead).
  const auto refuse_params = [&](const std::exception& e) {
    refuse(scene, spec.key_path + ".params", std::string("parameters a ") + spec.type + " accepts (" + e.what() + ")");
  };
  try {
    if (spec.type == kFmuNodeType) {
      BuiltFmuParticipant built = make_fmu_participant(scene, spec, coupling);
      node.fmu = std::move(built.participant);
      node.type = &node.fmu->node_type;
      node.block = std::move(built.block);
    } else {
      node.block = node.type->make_block(spec.params, coupling);
    }
    if (spec.fmu && !node.fmu) node.block = make_fmu_block(scene, spec, *node.type, *node.block, coupling);
  } catch (const std::invalid_argument& e) {
    refuse_params(e);
  } catch (const std::domain_error& e) {
    refuse_params(e);
  }
}

// A participant as the plan runs it: its node type, block, topic and published outputs.
PlannedNode plan_node(const config::Scene& scene, const config::ParticipantSpec& spec) {
  PlannedNode node;
  node.spec = &spec;
  node.type = find_node_type(spec.type);
  if (!node.type && spec.type != kFmuNodeType) {
    std::string known;
    for (const auto& t : node_types()) known += (known.empty() ? "" : ", ") + t.name;
    refuse(scene, spec.key_path + ".type", "expected a node type (" + known + ", fmu), got '" + spec.type + "'");
  }
  build_block(scene, spec, node);
  node.steps_itself = dynamic_cast<const fmi::CoSimulationBlock*>(node.block.get()) != nullptr;
  node.topic = spec.name + "/" + node.type->topic_suffix;
  for (const auto& field : node.type->publishes->fields) {
    // -1: a field this configuration does not compute (published as NaN).
    node.published_outputs.push_back(node.block->output_index(field.name));
  }
  return node;
}

// The node types' mapping of a topic connection's fields onto `to`'s inputs (those of
// `fields:` only, when the connection names them) into `edge`.
void map_group_fields(const config::Scene& scene, const config::ConnectionSpec& c, const InputGroup& group, const PlannedNode& to,
                      InboundEdge& edge) {
  for (const std::string& wanted : c.fields) {
    bool mapped = false;
    std::string known;
    for (const auto& [field, input] : group.field_to_input) {
      mapped = mapped || field == wanted;
      known += (known.empty() ? "" : ", ") + field;
    }
    if (!mapped)
      refuse(scene, c.key_path + ".fields", "expected fields of " + edge.type->idl_name + " that a " + to.type->name +
                                                " reads (" + known + "), got '" + wanted + "'");
  }
  for (const auto& [field, input] : group.field_to_input) {
    if (!c.fields.empty() && std::find(c.fields.begin(), c.fields.end(), field) == c.fields.end()) continue;
    int f = edge.type->field_index(field), i = to.block->input_index(input);
    if (f < 0) throw std::logic_error("catalog maps unknown field " + field);
    if (i < 0) continue;  // an input this configuration of the block does not use
    for (const auto& other : to.inputs)
      for (const auto& [of, oi] : other.field_to_input)
        if (oi == i) refuse(scene, c.key_path, "expected each input of '" + c.to + "' fed once: input '" + input + "' is already fed by '" + other.from + "'");
    edge.field_to_input.emplace_back(f, i);
  }
}

// `initial: {field: value}` — the partner's fields before its first sample (Jacobi only).
void parse_initial_values(const config::ConfigNode& ini, const config::ConnectionSpec& c, InboundEdge& edge) {
  if (!ini.is_map()) ini.fail("expected a map {topic field: value}, e.g. {drive_load_inertia: 2.5 kg m^2}");
  if (c.order != config::EdgeOrder::jacobi)
    ini.fail("expected no initial values on a gauss_seidel edge (it waits for the partner's step-0 sample)");
  for (const std::string& key : ini.keys()) {
    const int f = edge.type->field_index(key);
    bool fed = false;
    for (const auto& [ef, ei] : edge.field_to_input) fed = fed || ef == f;
    if (!fed) ini.child(key).fail("expected a field of " + edge.type->idl_name + " that this connection reads");
    double v = 0.0;
    try {
      v = config::parse_quantity(ini.child(key).as_string()).value_si;
    } catch (const std::exception& e) {
      ini.child(key).fail(std::string("expected a value (SI, or with its unit): ") + e.what());
    }
    edge.initial_values.emplace_back(f, v);
  }
}

// A connection of whole topics: the node types' own mapping of `from`'s topic onto `to`.
void plan_topic_connection(const config::Scene& scene, const config::ConnectionSpec& c, PlannedNode& from, PlannedNode& to) {
  if (from.fmu || to.fmu)
    refuse(scene, c.key_path, "expected a port-level connection (from: " + c.from + ".OUTPUT, to: " + c.to +
                                  ".INPUT) to or from an FMU participant");
  const InputGroup* group = to.type->group_for(*from.type->publishes);
  if (!group)
    refuse(scene, c.key_path, "expected a connection the node types support: a " + to.type->name +
                                  " cannot read the " + from.type->publishes->idl_name + " of a " + from.type->name);
  InboundEdge edge;
  edge.from = c.from;
  edge.topic = from.topic;
  edge.type = from.type->publishes;
  edge.order = c.order;
  edge.reconstruction = c.reconstruction;
  map_group_fields(scene, c, *group, to, edge);
  if (c.initial) parse_initial_values(*c.initial, c, edge);
  if (edge.field_to_input.empty())
    refuse(scene, c.key_path, "expected a connection that feeds an input of '" + c.to + "': as configured, it reads nothing from '" + c.from + "'");
  to.inputs.push_back(std::move(edge));
  ++from.subscriber_count;
}

}  // namespace

// The passes of a time run's plan, in order: each relies on the ones before it (and the first
// error found is the one reported).
ScenePlan ScenePlan::build_time_run(const config::Scene& scene) {
  ScenePlan plan;
  plan.scene_ = &scene;
  plan.place_nodes();
  plan.resolve_edges();
  plan.mark_watched_outputs();
  plan.check_required_inputs();
  plan.order_gauss_seidel();
  plan.check_algebraic_loops();
  plan.resolve_signals();
  plan.land_on_scheduled_events();  // after the edges: angle events follow the `angle` input to its publisher
  return plan;
}

void ScenePlan::place_nodes() {
  for (const auto& spec : scene_->participants) nodes_.push_back(plan_node(*scene_, spec));
}

void ScenePlan::resolve_edges() {
  const config::Scene& scene = *scene_;
  for (const auto& c : scene.connections) {
    PlannedNode& from = node(c.from);
    PlannedNode& to = node(c.to);
    if (c.coupling && coupling::parse_coupling(*c.coupling).scheme == coupling::CouplingScheme::interface_jacobian)
      coupling::plan_interface_jacobian_cut(scene, c, from, to);
    else if (!c.from_field.empty())
      plan_port_connection(scene, c, from, to);
    else
      plan_topic_connection(scene, c, from, to);
  }
}

void ScenePlan::mark_watched_outputs() {
  // The outputs that matter beyond their node: compared, or read by another participant.
  for (auto& node : nodes_) {
    std::set<int> watched;
    for (const auto& signal : scene_->compare)
      if (signal.participant == node.name())
        if (const int o = node.block->output_index(signal.output); o >= 0) watched.insert(o);
    for (const auto& other : nodes_)
      for (const auto& edge : other.inputs)
        if (edge.from == node.name())
          for (const auto& [field, input] : edge.field_to_input)
            if (const int o = node.published_outputs.at(static_cast<std::size_t>(field)); o >= 0) watched.insert(o);
    node.watched_outputs.assign(watched.begin(), watched.end());
  }
  // The launcher's recorder reads too: a node starts only once its writer has matched it,
  // or the recording could miss the first steps (a match is seen by each side on its own).
  if (scene_->record)
    for (auto& node : nodes_) node.recorded = scene_->record->records(node.topic);
}

void ScenePlan::check_required_inputs() const {
  for (const auto& node : nodes_) {
    for (int i = 0; i < node.block->num_inputs(); ++i) {
      if (!node.block->inputs()[i].required) continue;
      bool fed = false;
      for (const auto& e : node.inputs)
        for (const auto& fi : e.field_to_input) fed = fed || fi.second == i;
      if (!fed)
        refuse(*scene_, "connections", "expected a connection feeding the required input '" + node.block->inputs()[i].name +
                                           "' of '" + node.name() + "' (" + node.type->name + ")");
    }
  }
}

int ScenePlan::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].name() == name) return static_cast<int>(i);
  return -1;
}

void ScenePlan::order_gauss_seidel() const {
  // Gauss-Seidel edges must be ordered without cycles.
  const int n = static_cast<int>(nodes_.size());
  std::vector<std::vector<int>> gs(n);
  for (int i = 0; i < n; ++i)
    for (const auto& e : nodes_[i].inputs)
      if (e.order == config::EdgeOrder::gauss_seidel) gs[index_of(e.from)].push_back(i);
  if (auto cycle = find_cycle(gs); !cycle.empty()) {
    std::string names;
    for (int v : cycle) names += nodes_[v].name() + " -> ";
    refuse(*scene_, "connections", "expected Gauss-Seidel edges without cycles; found " + names + nodes_[cycle[0]].name() +
                                       " (declare one of these edges 'order: jacobi')");
  }
}

void ScenePlan::check_algebraic_loops() const {
  // Algebraic loops through direct feedthrough (port level): the monolithic reference
  // could not evaluate them.
  const int n = static_cast<int>(nodes_.size());
  std::vector<int> base(n + 1, 0);
  for (int i = 0; i < n; ++i) base[i + 1] = base[i] + nodes_[i].block->num_outputs();
  std::vector<std::vector<int>> ports(base[n]);
  for (int i = 0; i < n; ++i) {
    const auto& node = nodes_[i];
    for (const auto& e : node.inputs) {
      const auto& src = nodes_[index_of(e.from)];
      int src_index = index_of(e.from);
      for (const auto& [field, input] : e.field_to_input) {
        int src_out = src.published_outputs[field];
        if (src_out < 0)
          refuse(*scene_, "connections", "expected '" + e.from + "' to compute '" + src.type->publishes->fields[field].name +
                                             "', which '" + node.name() + "' reads; in its configuration it does not");
        for (int o = 0; o < node.block->num_outputs(); ++o)
          for (int ft : node.block->outputs()[o].feedthrough)
            if (ft == input) ports[base[src_index] + src_out].push_back(base[i] + o);
      }
    }
  }
  if (auto cycle = find_cycle(ports); !cycle.empty()) {
    std::string names;
    for (int v : cycle) {
      int i = 0;
      while (base[i + 1] <= v) ++i;
      names += nodes_[i].name() + "." + nodes_[i].block->outputs()[v - base[i]].name + " -> ";
    }
    refuse(*scene_, "connections", "expected no algebraic loop through direct feedthrough; found " + names + "...");
  }
}

void ScenePlan::resolve_signals() const {
  const config::Scene& scene = *scene_;
  for (const auto& s : scene.compare) resolve(s);
  for (const auto& r : scene.report) {
    resolve(r.signal);
    if (r.at) resolve(*r.at);
    for (const auto* list : {&r.supplied, &r.dissipated, &r.stored})
      for (const auto& s : *list) resolve(s);
  }
  // time.scales names topic fields: each must be one a participant publishes.
  if (scene.time.adaptive)
    for (const auto& [key, value] : scene.time.adaptive->scales) {
      const auto dot = key.find('.');
      const config::ParticipantSpec* p = dot == std::string::npos ? nullptr : scene.find_participant(key.substr(0, dot));
      if (!p) refuse(scene, "time.scales." + key.substr(0, dot), "expected a participant of this scene");
      const PlannedNode& publisher = node(p->name);
      if (publisher.type->publishes->field_index(key.substr(dot + 1)) < 0)
        refuse(scene, "time.scales." + key, "expected a field of " + publisher.type->publishes->idl_name + " (what '" + p->name + "' publishes)");
    }
}

const PlannedNode& ScenePlan::node(const std::string& name) const {
  for (const auto& n : nodes_)
    if (n.name() == name) return n;
  throw std::out_of_range("no participant " + name);
}

PlannedNode& ScenePlan::node(const std::string& name) {
  return const_cast<PlannedNode&>(static_cast<const ScenePlan&>(*this).node(name));
}

std::pair<int, int> ScenePlan::resolve(const config::SignalRef& ref) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].name() != ref.participant) continue;
    int out = nodes_[i].block->output_index(ref.output);
    if (out < 0) {
      std::string known;
      for (const auto& o : nodes_[i].block->outputs()) known += (known.empty() ? "" : ", ") + o.name;
      throw config::ConfigError(scene_->file, ref.key_path,
                                "expected an output of '" + ref.participant + "' (" + known + "), got '" + ref.output + "'");
    }
    return {static_cast<int>(i), out};
  }
  throw config::ConfigError(scene_->file, ref.key_path, "expected a participant of this scene, got '" + ref.participant + "'");
}

}  // namespace mechsim::cosim
