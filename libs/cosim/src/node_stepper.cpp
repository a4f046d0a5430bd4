#include "mechsim/cosim/node_stepper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mechsim::cosim {

solve::SolverOptions solver_options(const config::SolverSpec& spec) {
  solve::SolverOptions o;
  // config::solver_method_names() lists the methods in the order of solve::Method.
  const auto& names = config::solver_method_names();
  o.method = static_cast<solve::Method>(std::find(names.begin(), names.end(), spec.method) - names.begin());
  o.rtol = spec.rtol;
  o.atol = spec.atol;
  return o;
}

NodeStepper::NodeStepper(PlannedNode& node, std::shared_ptr<const StepGrid> grid, std::size_t participants, std::size_t self)
    : node_(node), grid_(std::move(grid)), self_(self) {
  const models::Block& block = *node.block;
  if (grid_->is_adaptive()) {
    // A block that neither integrates nor samples reads its inputs only at step ends: a
    // Gauss-Seidel edge into it makes no error (the samples there are exact), and a Jacobi
    // edge's error is all in its effect on the block's outputs.
    const bool reads_only_at_step_ends = block.num_states() == 0 && !(block.sample_time() > 0);
    const auto scale_of = [&](const std::string& key) {
      for (const auto& [name, value] : grid_->adaptive_spec().scales)
        if (name == key) return value;
      return 0.0;
    };
    std::vector<CouplingErrorEstimate::Edge> edges;
    for (const auto& edge : node.inputs) {
      CouplingErrorEstimate::Edge e{edge.order, edge.reconstruction, {}, std::vector<double>(edge.type->fields.size(), 0.0)};
      for (std::size_t f = 0; f < edge.type->fields.size(); ++f) e.scales[f] = scale_of(edge.from + "." + edge.type->fields[f].name);
      if (edge.order == config::EdgeOrder::jacobi && !node.cut) {
        // The watched outputs (not flags and counts: unit "1") the edge's inputs reach directly.
        for (const int o : node.watched_outputs) {
          const auto& port = block.outputs()[static_cast<std::size_t>(o)];
          if (port.unit == "1") continue;
          bool reached = false;
          for (const auto& [field, input] : edge.field_to_input)
            reached = reached || std::find(port.feedthrough.begin(), port.feedthrough.end(), input) != port.feedthrough.end();
          if (!reached) continue;
          e.outputs.push_back(static_cast<std::size_t>(o));
          e.output_scales.push_back(scale_of(node.name() + "." + port.name));
        }
      }
      if (!reads_only_at_step_ends)
        for (const auto& [field, input] : edge.field_to_input) e.fields.push_back(static_cast<std::size_t>(field));
      edges.push_back(std::move(e));
    }
    estimate_.emplace(std::move(edges));
    agreement_.emplace(participants, grid_->adaptive_spec(), grid_->end());
    for (const auto& events : node.run_time_angle_events) {
      AngleWatch w;
      w.angles = &events.angles;
      w.own_outputs = events.own_outputs;
      const auto index = [&](const char* name) { return w.own_outputs ? block.output_index(name) : block.input_index(name); };
      w.angle = index("angle");
      w.speed = index("speed");
      w.acceleration = index("acceleration");
      if (w.angle >= 0 && w.speed >= 0) angle_watches_.push_back(w);
    }
  }
  for (const auto& edge : node.inputs) {
    InputChannel channel(edge.order, edge.reconstruction, grid_);
    // A Jacobi edge's initial values are the defaults of the inputs it feeds.
    std::vector<double> initial(edge.type->fields.size(), 0.0);
    for (const auto& [field, input] : edge.field_to_input) initial[field] = block.inputs()[input].default_value;
    for (const auto& [field, value] : edge.initial_values) initial[field] = value;  // the scene's `initial:`
    channel.initial_values(initial);
    channels_.push_back(std::move(channel));
  }
  defaults_ = block.default_inputs();
  u_ = defaults_;
  y_.assign(block.num_outputs(), 0.0);
  event_row_.assign(y_.size(), 0.0);  // sized now: a real-time step must not allocate
  event_inputs_.assign(u_.size(), 0.0);
  x_.assign(block.num_states(), 0.0);
  block.initial_state(grid_->start(), x_);
  if (node.cut) cut_side_ = std::make_unique<coupling::InterfaceSide>(*node.block, node.cut->torque_input,
                                                                      node.cut->angle_output, node.cut->levels);
  spare_predictions_.reserve(4);
}

double NodeStepper::time() const { return grid_->time(k_); }

bool NodeStepper::can_initialise() const {
  for (const auto& c : channels_)
    if (!c.ready_for_initial()) return false;
  return true;
}

bool NodeStepper::inputs_ready(std::uint64_t k) const {
  for (const auto& c : channels_)
    if (!c.ready_for_step(k)) return false;
  return true;
}

bool NodeStepper::can_step() const {
  if (!initialised_ || finished() || !step_known() || !inputs_ready(k_)) return false;
  return !cut_side_ || (has_own_prediction_ && partner_predictions_.count(k_) > 0);
}

bool NodeStepper::prediction_due() const {
  return cut_side_ && initialised_ && !finished() && !has_own_prediction_ && step_known() && inputs_ready(k_);
}

bool NodeStepper::proposal_due() const {
  if (!agreement_ || !initialised_ || finished() || proposed_step_ == k_ || !grid_->knows_end_of(k_)) return false;
  if (grid_->at_end(k_ + 1)) return false;  // step k is the last: nothing after it to propose
  // The estimate compares what a Jacobi edge reconstructed at t_k with the partner's step-k
  // sample; a Gauss-Seidel edge's step-k sample is here already (the step to t_k needed it).
  for (std::size_t e = 0; e < channels_.size(); ++e)
    if (channels_[e].order() == config::EdgeOrder::jacobi && !channels_[e].ready_for_step(k_)) return false;
  return true;
}

StepProposal NodeStepper::propose() {
  if (!proposal_due()) throw std::logic_error("step proposal before the step's Jacobi inputs arrived");
  const config::AdaptiveStepSpec& spec = grid_->adaptive_spec();
  for (std::size_t e = 0; e < channels_.size(); ++e) {
    if (channels_[e].order() != config::EdgeOrder::jacobi) continue;
    const std::vector<double>& sample = channels_[e].held_samples().at(k_);
    const std::vector<std::size_t>& watched = estimate_->outputs(e);
    if (watched.empty()) {
      estimate_->received(e, k_, sample);
      continue;
    }
    // The outputs at t_k had the partner's sample been there instead of what was used.
    effect_u_ = u_;
    effect_y_.resize(y_.size());
    for (const auto& [field, input] : node_.inputs[e].field_to_input) effect_u_[input] = sample[field];
    node_.block->calc_outputs(time(), integrator_->state(), effect_u_, effect_y_);
    effect_change_.resize(watched.size());
    for (std::size_t j = 0; j < watched.size(); ++j) effect_change_[j] = effect_y_[watched[j]] - y_[watched[j]];
    estimate_->received(e, k_, sample, y_, effect_change_);
  }
  // Made at step k, for the step after the next, k+1 -> k+2 (t_k+1 is agreed already): the
  // proposals travel while the nodes take step k -> k+1, so no node waits for them.
  const double t_next = grid_->time(k_ + 1);
  // After a discontinuity (or a law joint) the controller starts again from its initial
  // step, like an integrator after an event: the step before says nothing of what follows.
  const bool restart = grid_->is_event(k_ + 1);
  const double current_h = restart ? 0.0 : grid_->step_length(k_);
  const auto estimate = estimate_->at(k_, spec.tolerance, current_h);
  StepProposal p = propose_step(spec, current_h, estimate);
  if (channels_.empty()) p.step_length = spec.max;  // no inputs: no coupling error of its own
  // The participants' scheduled discontinuities: every node knows them (the plan), every
  // node's proposal lands on the next one.
  const double event = std::min(grid_->next_scheduled_event(t_next), next_angle_event(t_next));
  p.event_time = event;
  p.event = std::isfinite(event);
  // A sampled block's ticks are landed on too, but they are not events: its held output
  // changes there, which a step that ends on the tick exchanges exactly, and the controller
  // goes on from the step before (restarting after every tick would pin the step to
  // `initial`). So no step is longer than the sample time.
  if (const double tick = next_sample_tick(t_next); tick < p.event_time) {
    p.event_time = tick;
    p.event = false;
  }
  // A replayed participant steps where the recorded run stepped (it has no opinion of its own).
  if (const double recorded = node_.block->next_instant_after(t_next); std::isfinite(recorded)) {
    p.step_length = spec.max;
    p.event_time = recorded;
    p.event = recorded == event;
  }
  if (state_event_step_ == k_) p.state_event_time = state_event_time_;
  proposed_step_ = k_;
  add_proposal(self_, k_, p);
  return p;
}

double NodeStepper::next_sample_tick(double t_next) const {
  const double ts = node_.block->sample_time();
  if (!(ts > 0)) return std::numeric_limits<double>::infinity();
  // The instants BlockIntegrator samples at (its origin is the run's start); one within
  // `min` after t_next is taken inside the step (no sliver of a step).
  const double t0 = grid_->start();
  return solve::sample_instant(t0, ts, solve::first_sample_after(t0, ts, t_next + grid_->adaptive_spec().min));
}

double NodeStepper::next_angle_event(double t_next) {
  double first = std::numeric_limits<double>::infinity();
  for (AngleWatch& w : angle_watches_) {
    // The crossing announced with the last proposal set t_k+1: landed, not to be landed again.
    if (w.announced.t == t_next) w.passed = w.announced.target;
    const std::vector<double>& v = w.own_outputs ? y_ : u_;
    const ShaftMotion motion{time(), v[static_cast<std::size_t>(w.angle)], v[static_cast<std::size_t>(w.speed)],
                             w.acceleration >= 0 ? v[static_cast<std::size_t>(w.acceleration)] : 0.0};
    // Not within `min` after t_k+1: that crossing is taken as on the boundary (no sliver of a step).
    // No upper bound: the agreement lands on it only when it comes within the step, and the
    // prediction is made afresh at every step (a replayed node, whose own step differs, finds
    // the same crossing).
    w.announced = predict_angle_event(motion, *w.angles, t_next + grid_->adaptive_spec().min,
                                      std::numeric_limits<double>::infinity(), w.passed);
    first = std::min(first, w.announced.t);
  }
  return first;
}

void NodeStepper::add_proposal(std::size_t participant, std::uint64_t step, const StepProposal& proposal) {
  if (!agreement_) throw std::logic_error("step proposal in a run with a fixed macro step");
  if (step + 2 <= grid_->steps()) return;  // agreed already: it set t_step+2
  if (!agreement_->add(participant, step, proposal))
    throw std::runtime_error("two different step proposals of participant " + std::to_string(participant) + " for step " +
                             std::to_string(step) + ": a participant that does not belong to this run writes into it");
  agree_if_complete();
}

std::vector<std::size_t> NodeStepper::missing_proposals() const {
  if (!agreement_ || step_known() || grid_->steps() == 0) return {};
  return agreement_->missing(grid_->steps() - 1);  // the proposals that set the next instant
}

void NodeStepper::agree_if_complete() {
  // The proposals made at step j set t_j+2. (Another node of this process may have extended
  // a shared grid already: extend() then checks that it agreed the same.)
  if (grid_->steps() > 0) agreement_->discard_before(grid_->steps() - 1);
  for (;;) {
    const std::uint64_t n = grid_->steps();  // t_n is the last instant known
    if (n == 0 || grid_->at_end(n) || !agreement_->complete(n - 1)) break;
    const AgreedStep a = agreement_->agreed(n - 1, grid_->time(n));
    if (a.after_state_event) estimate_->discontinuity_at(n - 1);
    grid_->extend(n, a.t_next, a.event);
    agreement_->discard_before(n);
  }
}

void NodeStepper::predict(std::vector<double>& prediction_fields) {
  if (!prediction_due()) throw std::logic_error("prediction before the step's inputs arrived");
  const std::uint64_t k = k_;
  cut_side_->predict(*integrator_, grid_->time(k + 1),
                     [this, k](double t, std::span<double> u) { inputs_at(t, k, u); }, assumed_torque_, own_prediction_);
  has_own_prediction_ = true;
  coupling::to_fields(own_prediction_, prediction_fields);
}

void NodeStepper::add_partner_prediction(std::uint64_t step, std::span<const double> fields) {
  if (step + 1 < k_) return;  // stale
  if (partner_predictions_.count(step)) return;  // a duplicate
  if (spare_predictions_.empty()) {
    partner_predictions_.emplace(step, coupling::from_fields(fields));
    return;
  }
  auto node = std::move(spare_predictions_.back());
  spare_predictions_.pop_back();
  node.key() = step;
  coupling::from_fields(fields, node.mapped());
  partner_predictions_.insert(std::move(node));
}

void NodeStepper::initial_inputs(std::span<double> u) {
  for (std::size_t e = 0; e < channels_.size(); ++e) {
    channels_[e].initial_values_at(scratch_);
    for (const auto& [field, input] : node_.inputs[e].field_to_input) u[input] = scratch_[field];
  }
}

void NodeStepper::inputs_at(double t, std::uint64_t k, std::span<double> u) {
  std::copy(defaults_.begin(), defaults_.end(), u.begin());  // unconnected inputs
  for (std::size_t e = 0; e < channels_.size(); ++e) {
    channels_[e].values_at(t, k, scratch_);
    for (const auto& [field, input] : node_.inputs[e].field_to_input) u[input] = scratch_[field];
  }
}

void NodeStepper::publishable(std::vector<double>& topic_values) const {
  topic_values.resize(node_.published_outputs.size());
  for (std::size_t f = 0; f < topic_values.size(); ++f) {
    const int out = node_.published_outputs[f];
    topic_values[f] = out >= 0 ? y_[out] : std::numeric_limits<double>::quiet_NaN();
  }
}

void NodeStepper::initialise(std::vector<double>& topic_values) {
  if (!can_initialise()) throw std::logic_error("initialise before the Gauss-Seidel inputs of step 0 arrived");
  initial_inputs(u_);
  integrator_ = std::make_unique<solve::BlockIntegrator>(*node_.block, solver_options(node_.spec->solver), grid_->start(), x_);
  // A sampled block takes its t0 sample now, so that its step-0 outputs are what it holds
  // over [t0, t1], as in the reference (which samples at t0 before its first step).
  if (node_.block->sample_time() > 0)
    integrator_->advance_to(grid_->start(), [this](double, std::span<double> u) { std::copy(u_.begin(), u_.end(), u.begin()); });
  node_.block->calc_outputs(grid_->start(), integrator_->state(), u_, y_);
  publishable(topic_values);
  k_ = 0;
  initialised_ = true;
}

void NodeStepper::step(std::vector<double>& topic_values) {
  if (!can_step()) throw std::logic_error("step before its inputs arrived");
  const std::uint64_t k = k_;
  // Index-based time, never accumulated (the grid's t_k+1).
  const double t_next = grid_->time(k + 1);
  const auto inputs = [this, k](double t, std::span<double> u) { inputs_at(t, k, u); };
  event_row_ready_ = grid_->is_event(k);
  if (event_row_ready_) {
    std::copy(y_.begin(), y_.end(), event_row_.begin());
    if (!cut_side_) {
      inputs_at(time(), k, event_inputs_);
      node_.block->calc_outputs(time(), integrator_->state(), event_inputs_, event_row_);
    }
  }
  if (cut_side_) {
    // Both sides solve the same system with the "+" side's prediction first: equal torques.
    const PlannedCut& cut = *node_.cut;
    const auto& partner = partner_predictions_.at(k);
    const auto& plus = cut.twist_sign > 0 ? own_prediction_ : partner;
    const auto& minus = cut.twist_sign > 0 ? partner : own_prediction_;
    std::vector<double>& levels = levels_;
    coupling::solve_torque_levels({cut.stiffness, cut.damping}, t_next - time(), plus, minus, levels);
    cut_side_->advance(*integrator_, t_next, inputs, levels);
    assumed_torque_ = levels.back();
    end_torque_ = levels.size() > 1 ? 1.5 * levels.back() - 0.5 * levels[levels.size() - 2] : levels.back();
    has_own_prediction_ = false;
    while (!partner_predictions_.empty() && partner_predictions_.begin()->first <= k) {
      if (spare_predictions_.size() < 4) spare_predictions_.push_back(partner_predictions_.extract(partner_predictions_.begin()));
      else partner_predictions_.erase(partner_predictions_.begin());
    }
  } else {
    integrator_->mark_discontinuity();  // the reconstructed inputs start afresh each step
    integrator_->advance_to(t_next, inputs);
  }
  // A root found inside the step (lift-off, landing): the adaptive step is told (propose).
  for (auto& found : integrator_->take_events()) {
    state_event_step_ = k + 1;
    state_event_time_ = found.t;
    found_events_.push_back(found);
  }
  for (std::size_t e = 0; e < channels_.size(); ++e) {
    channels_[e].values_at_step_end(k, scratch_);
    for (const auto& [field, input] : node_.inputs[e].field_to_input) u_[input] = scratch_[field];
    if (estimate_) estimate_->used_at_step_end(e, k + 1, t_next, scratch_, grid_->is_event(k + 1));
  }
  // The torque published at t_k+1: the last two levels (means over their sub-intervals)
  // extrapolated to the step's end; the same on both sides.
  if (cut_side_) u_[node_.cut->torque_input] = end_torque_;
  node_.block->calc_outputs(t_next, integrator_->state(), u_, y_);
  publishable(topic_values);
  k_ = k + 1;
  for (auto& c : channels_) c.discard_before(k_);
}

std::vector<solve::EventRecord> NodeStepper::take_events() {
  std::vector<solve::EventRecord> out = std::move(found_events_);
  found_events_.clear();
  if (integrator_)
    for (auto& e : integrator_->take_events()) out.push_back(e);
  return out;
}

std::vector<double> NodeStepper::coupled_state() const {
  if (!integrator_) throw std::logic_error("coupled_state before initialise");
  const auto x = integrator_->state();
  std::vector<double> z(x.begin(), x.end());
  const std::vector<double> held = node_.block->save_discrete_state();
  z.insert(z.end(), held.begin(), held.end());
  for (const auto& c : channels_)
    for (const auto& [step, values] : c.held_samples()) z.insert(z.end(), values.begin(), values.end());
  if (cut_side_) z.push_back(assumed_torque_);
  return z;
}

void NodeStepper::set_coupled_state(std::span<const double> z) {
  if (z.size() != coupled_state().size()) throw std::invalid_argument("set_coupled_state: size mismatch");
  const std::size_t nx = integrator_->state().size();
  const std::size_t nd = node_.block->save_discrete_state().size();
  std::size_t i = nx + nd;
  integrator_->reset_state(integrator_->time(), z.first(nx));
  if (nd > 0) node_.block->restore_discrete_state(z.subspan(nx, nd));
  for (auto& c : channels_)
    for (auto& [step, values] : c.held_samples())
      for (double& v : values) v = z[i++];
  if (cut_side_) assumed_torque_ = z[i++];
}

StepperSnapshot NodeStepper::snapshot() const {
  if (!integrator_) throw std::logic_error("snapshot before initialise");
  StepperSnapshot s;
  s.step = k_;
  const auto x = integrator_->state();
  s.state.assign(x.begin(), x.end());
  s.discrete = node_.block->save_discrete_state();
  s.outputs = y_;
  for (const auto& c : channels_) {
    auto& held = s.channels.emplace_back();
    for (const auto& [step, values] : c.held_samples())
      if (step < k_) held.emplace_back(step, values);
  }
  s.assumed_torque = assumed_torque_;
  return s;
}

void NodeStepper::restore(const StepperSnapshot& s, std::vector<double>& topic_values) {
  const std::string who = "restore of node '" + node_.name() + "'";
  if (s.state.size() != x_.size() || s.outputs.size() != y_.size() || s.channels.size() != channels_.size())
    throw std::invalid_argument(who + ": the checkpoint does not fit this node (state, outputs or channels differ)");
  if (s.step > grid_->steps()) throw std::invalid_argument(who + ": checkpoint step " + std::to_string(s.step) + " is past the run's end");
  if (!integrator_) {
    integrator_ = std::make_unique<solve::BlockIntegrator>(*node_.block, solver_options(node_.spec->solver), grid_->start(), x_);
    // The t0 sample is behind a restored node, as behind one that initialised (it is
    // overwritten by the restored discrete state below).
    if (node_.block->sample_time() > 0)
      integrator_->advance_to(grid_->start(), [this](double, std::span<double> u) { std::copy(defaults_.begin(), defaults_.end(), u.begin()); });
  }
  const double t = grid_->time(s.step);
  // A new time resumes the sample grid after t: the sample at t was taken before the checkpoint.
  integrator_->reset_state(t, s.state);
  if (!s.discrete.empty() || !node_.block->save_discrete_state().empty()) node_.block->restore_discrete_state(s.discrete);
  for (std::size_t e = 0; e < channels_.size(); ++e) {
    auto& held = channels_[e].held_samples();
    held.clear();
    for (const auto& [step, values] : s.channels[e]) held.emplace(step, values);
  }
  y_ = s.outputs;
  k_ = s.step;
  assumed_torque_ = s.assumed_torque;
  has_own_prediction_ = false;
  partner_predictions_.clear();
  initialised_ = true;
  publishable(topic_values);
}

}  // namespace mechsim::cosim
