#include "mechsim/fmi/model_exchange_block.h"

namespace mechsim::fmi {

namespace {

std::string unit_of(const Variable& v) { return v.unit.empty() ? "1" : v.unit; }

// Ends an event iteration: refuses what the block cannot honour.
void check_update(const DiscreteUpdate& update, const FmuLabel& label, double t) {
  if (update.terminate)
    throw FmuError(label, "asked to terminate the simulation at t = " + std::to_string(t) + " s");
  if (update.next_event_time_defined)
    throw FmuError(label, "schedules a time event (nextEventTime = " + std::to_string(update.next_event_time) +
                              " s); FMU time events are not supported yet");
}

}  // namespace

ModelExchangeBlock::ModelExchangeBlock(const FmuArchive& archive, const std::map<std::string, double>& parameters,
                                       double t0, double t_stop)
    : Block("fmu"), archive_(archive) {
  const ModelDescription& md = archive.description();
  const FmuLabel& label = archive.label();
  for (const auto& v : md.variables) {
    if (v.type == ValueType::other) continue;
    if (v.causality == Causality::input) {
      inputs_.push_back(&v);
      double start = 0.0;
      if (v.start) start = v.type == ValueType::boolean ? (*v.start == "true" || *v.start == "1") : std::stod(*v.start);
      declare_input(v.name, unit_of(v), start);
    }
  }
  std::vector<int> all_inputs(inputs_.size());
  for (std::size_t i = 0; i < all_inputs.size(); ++i) all_inputs[i] = static_cast<int>(i);
  for (const auto& v : md.variables) {
    if (v.type == ValueType::other || v.causality != Causality::output) continue;
    outputs_.push_back(&v);
    declare_output(v.name, unit_of(v), all_inputs);
  }
  for (int i = 0; i < md.number_of_continuous_states; ++i) {
    const int v = md.state_variables[static_cast<std::size_t>(i)];
    if (v >= 0)
      declare_state(md.variables[static_cast<std::size_t>(v)].name, md.variables[static_cast<std::size_t>(v)].unit);
    else
      declare_state("state[" + std::to_string(i) + "]", "");
  }
  num_indicators_ = md.number_of_event_indicators;

  // Refuse unknown parameters before anything runs.
  for (const auto& [name, value] : parameters) {
    const Variable* v = md.find_variable(name);
    if (v == nullptr) throw FmuError(label, "has no variable '" + name + "' (a parameter set in the scene)");
    if (v->causality != Causality::parameter || v->type == ValueType::other)
      throw FmuError(label, "variable '" + name + "' has causality " + std::string(to_string(v->causality)) +
                                " and type " + v->type_element +
                                "; the scene sets parameters of type Real/Float64, Integer/Int32 or Boolean");
  }
  fmu_ = FmuInstance::create(archive, InterfaceKind::model_exchange, label.participant.empty() ? "fmu" : label.participant);
  fmu_->enter_initialization(t0, t_stop);
  for (const auto& [name, value] : parameters) set_value(*md.find_variable(name), value);
  fmu_->exit_initialization();
  check_update(fmu_->update_discrete_states(), label, t0);
  fmu_->enter_continuous_time_mode();
  x0_.resize(static_cast<std::size_t>(num_states()));
  fmu_->get_continuous_states(x0_);
}

void ModelExchangeBlock::set_value(const Variable& v, double value) const {
  switch (v.type) {
    case ValueType::real: fmu_->set_real(v.value_reference, value); break;
    case ValueType::integer: fmu_->set_integer(v.value_reference, static_cast<std::int32_t>(value)); break;
    case ValueType::boolean: fmu_->set_boolean(v.value_reference, value != 0.0); break;
    case ValueType::other: break;
  }
}

double ModelExchangeBlock::get_value(const Variable& v) const {
  switch (v.type) {
    case ValueType::real: return fmu_->get_finite_real(v);
    case ValueType::integer: return fmu_->get_integer(v.value_reference);
    case ValueType::boolean: return fmu_->get_boolean(v.value_reference) ? 1.0 : 0.0;
    case ValueType::other: break;
  }
  return 0.0;
}

void ModelExchangeBlock::load(double t, std::span<const double> x, std::span<const double> u) const {
  fmu_->set_time(t);
  if (!x.empty()) fmu_->set_continuous_states(x);
  for (std::size_t i = 0; i < inputs_.size(); ++i) set_value(*inputs_[i], u[i]);
}

void ModelExchangeBlock::initial_state(double, std::span<double> x) const {
  std::copy(x0_.begin(), x0_.end(), x.begin());
}

void ModelExchangeBlock::derivatives(double t, std::span<const double> x, std::span<const double> u,
                                     std::span<double> dxdt) const {
  load(t, x, u);
  if (!dxdt.empty()) fmu_->get_derivatives(dxdt);
}

void ModelExchangeBlock::calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                                      std::span<double> y) const {
  load(t, x, u);
  for (std::size_t i = 0; i < outputs_.size(); ++i) y[i] = get_value(*outputs_[i]);
}

void ModelExchangeBlock::event_functions(double t, std::span<const double> x, std::span<const double> u,
                                         std::span<double> g) const {
  load(t, x, u);
  fmu_->get_event_indicators(g);
}

bool ModelExchangeBlock::handle_events(double t, std::span<double> x, std::span<const double> u,
                                       std::span<const int>) {
  load(t, x, u);
  fmu_->enter_event_mode();
  const DiscreteUpdate update = fmu_->update_discrete_states();
  check_update(update, archive_.label(), t);
  fmu_->enter_continuous_time_mode();
  if (update.states_changed) fmu_->get_continuous_states(x);
  return update.states_changed;
}

}  // namespace mechsim::fmi
