#include "mechsim/cosim/node_stepper.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace mechsim::cosim {

solve::SolverOptions solver_options(const config::SolverSpec& spec) {
  solve::SolverOptions o;
  o.method = spec.method == "cvode_adams" ? solve::Method::cvode_adams : solve::Method::cvode_bdf;
  o.rtol = spec.rtol;
  o.atol = spec.atol;
  return o;
}

NodeStepper::NodeStepper(PlannedNode& node, const config::TimeSpec& time)
    : node_(node), t0_(time.start), h_(time.step), n_steps_(static_cast<std::uint64_t>(time.steps())) {
  const models::Block& block = *node.block;
  for (const auto& edge : node.inputs) {
    InputChannel channel(edge.order, edge.reconstruction, t0_, h_);
    // A Jacobi edge's initial values are the defaults of the inputs it feeds.
    std::vector<double> initial(edge.type->fields.size(), 0.0);
    for (const auto& [field, input] : edge.field_to_input) initial[field] = block.inputs()[input].default_value;
    channel.initial_values(initial);
    channels_.push_back(std::move(channel));
  }
  defaults_ = block.default_inputs();
  u_ = defaults_;
  y_.assign(block.num_outputs(), 0.0);
  x_.assign(block.num_states(), 0.0);
  block.initial_state(t0_, x_);
}

double NodeStepper::time() const { return t0_ + static_cast<double>(k_) * h_; }

bool NodeStepper::can_initialise() const {
  for (const auto& c : channels_)
    if (!c.ready_for_initial()) return false;
  return true;
}

bool NodeStepper::can_step() const {
  if (!initialised_ || finished()) return false;
  for (const auto& c : channels_)
    if (!c.ready_for_step(k_)) return false;
  return true;
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
  integrator_ = std::make_unique<solve::BlockIntegrator>(*node_.block, solver_options(node_.spec->solver), t0_, x_);
  node_.block->calc_outputs(t0_, integrator_->state(), u_, y_);
  publishable(topic_values);
  k_ = 0;
  initialised_ = true;
}

void NodeStepper::step(std::vector<double>& topic_values) {
  if (!can_step()) throw std::logic_error("step before its inputs arrived");
  const std::uint64_t k = k_;
  // Index-based time, never accumulated: t_k+1 = t0 + (k+1) H.
  const double t_next = t0_ + static_cast<double>(k + 1) * h_;
  integrator_->mark_discontinuity();  // the reconstructed inputs start afresh each step
  integrator_->advance_to(t_next, [this, k](double t, std::span<double> u) { inputs_at(t, k, u); });
  for (std::size_t e = 0; e < channels_.size(); ++e) {
    channels_[e].values_at_step_end(k, scratch_);
    for (const auto& [field, input] : node_.inputs[e].field_to_input) u_[input] = scratch_[field];
  }
  node_.block->calc_outputs(t_next, integrator_->state(), u_, y_);
  publishable(topic_values);
  k_ = k + 1;
  for (auto& c : channels_) c.discard_before(k_);
}

std::vector<solve::EventRecord> NodeStepper::take_events() {
  return integrator_ ? integrator_->take_events() : std::vector<solve::EventRecord>{};
}

}  // namespace mechsim::cosim
