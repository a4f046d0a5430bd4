#include "mechsim/fmi/model_exchange_block.h"

#include "exchanged_variables.h"

namespace mechsim::fmi {

namespace {

// Ends an event iteration: refuses what the block cannot honour.
void check_update(const DiscreteUpdate& update, const FmuLabel& label, double t) {
  if (update.terminate)
    throw FmuError(label, "asked to terminate the simulation at t = " + std::to_string(t) + " s");
  if (update.next_event_time_defined)
    throw FmuError(label, "schedules a time event (nextEventTime = " + std::to_string(update.next_event_time) +
                              " s); FMU time events are not supported yet");
}

}  // namespace

ModelExchangeBlock::ModelExchangeBlock(std::shared_ptr<const FmuArchive> archive_in, const std::map<std::string, double>& parameters,
                                       double t0, double t_stop)
    : Block("fmu"), archive_(std::move(archive_in)) {
  const FmuArchive& archive = *archive_;
  const ModelDescription& md = archive.description();
  const ExchangedVariables ports = exchanged_variables(md);
  inputs_ = ports.inputs;
  outputs_ = ports.outputs;
  for (const Variable* v : inputs_) declare_input(v->name, port_unit(*v), start_value(*v, archive.label()));
  std::vector<int> all_inputs(inputs_.size());
  for (std::size_t i = 0; i < all_inputs.size(); ++i) all_inputs[i] = static_cast<int>(i);
  for (const Variable* v : outputs_) declare_output(v->name, port_unit(*v), all_inputs);
  for (int i = 0; i < md.number_of_continuous_states; ++i) {
    const int v = md.state_variables[static_cast<std::size_t>(i)];
    if (v >= 0)
      declare_state(md.variables[static_cast<std::size_t>(v)].name, md.variables[static_cast<std::size_t>(v)].unit);
    else
      declare_state("state[" + std::to_string(i) + "]", "");
  }
  num_indicators_ = md.number_of_event_indicators;

  fmu_ = initialize(archive, InterfaceKind::model_exchange, parameters, t0, t_stop);
  check_update(fmu_->update_discrete_states(), archive.label(), t0);
  fmu_->enter_continuous_time_mode();
  x0_.resize(static_cast<std::size_t>(num_states()));
  fmu_->get_continuous_states(x0_);
}

void ModelExchangeBlock::load(double t, std::span<const double> x, std::span<const double> u) const {
  fmu_->set_time(t);
  if (!x.empty()) fmu_->set_continuous_states(x);
  for (std::size_t i = 0; i < inputs_.size(); ++i) set_value(*fmu_, *inputs_[i], u[i]);
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
  for (std::size_t i = 0; i < outputs_.size(); ++i) y[i] = get_value(*fmu_, *outputs_[i]);
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
  check_update(update, archive_->label(), t);
  fmu_->enter_continuous_time_mode();
  if (update.states_changed) fmu_->get_continuous_states(x);
  return update.states_changed;
}

}  // namespace mechsim::fmi
