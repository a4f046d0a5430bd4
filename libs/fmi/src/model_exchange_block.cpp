#include "mechsim/fmi/model_exchange_block.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "exchanged_variables.h"
#include "lazy_instance.h"
#include "saved_state.h"

namespace mechsim::fmi {

namespace {

constexpr double kNone = std::numeric_limits<double>::infinity();

std::string seconds(double t) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g s", t);
  return text;
}

}  // namespace

ModelExchangeBlock::ModelExchangeBlock(std::shared_ptr<const FmuArchive> archive_in, const std::map<std::string, double>& parameters,
                                       double t0, double t_stop)
    : Block("fmu"), archive_(std::move(archive_in)), next_time_event_(kNone) {
  const FmuArchive& archive = *archive_;
  const ModelDescription& md = archive.description();
  const ExchangedVariables ports = exchanged_variables(md);
  inputs_ = ports.inputs;
  outputs_ = ports.outputs;
  for (const Variable* v : inputs_) declare_input(v->name, port_unit(*v), start_value(*v, archive.label()));
  for (const Variable* v : outputs_) declare_output(v->name, port_unit(*v), feedthrough(md, *v, inputs_));
  for (int i = 0; i < md.number_of_continuous_states; ++i) {
    const int v = md.state_variables[static_cast<std::size_t>(i)];
    if (v >= 0)
      declare_state(md.variables[static_cast<std::size_t>(v)].name, md.variables[static_cast<std::size_t>(v)].unit);
    else
      declare_state("state[" + std::to_string(i) + "]", "");
  }
  num_indicators_ = md.number_of_event_indicators;
  // With states the integrator's root finding lands on it; without, the integrator bisects
  // on time (solve's stateless events): a staircase or a sampled controller runs either way.
  has_time_events_ = true;
  can_save_state_ = missing_state_capabilities(md, InterfaceKind::model_exchange).empty();

  x0_.resize(static_cast<std::size_t>(num_states()));
  fmu_ = std::make_unique<LazyInstance>(
      [this, parameters, t0, t_stop] { return initialize(*archive_, InterfaceKind::model_exchange, parameters, t0, t_stop); },
      [this, t0](FmuInstance& fmu) {
        take_update(fmu.update_discrete_states(), t0);
        fmu.enter_continuous_time_mode();
        fmu.get_continuous_states(x0_);
      });
  fmu_->make_unless_deferred();
}

ModelExchangeBlock::~ModelExchangeBlock() = default;
void ModelExchangeBlock::instantiate_now() const { fmu_->get(); }
FmuInstance& ModelExchangeBlock::fmu() const { return fmu_->get(); }

void ModelExchangeBlock::take_update(const DiscreteUpdate& update, double t) const {
  const FmuLabel& label = archive_->label();
  if (update.terminate) throw FmuError(label, "asked to terminate the simulation at t = " + seconds(t));
  next_time_event_ = kNone;
  if (!update.next_event_time_defined) return;
  if (!(update.next_event_time > t))
    throw FmuError(label, "schedules a time event at " + seconds(update.next_event_time) +
                              ", not after the event at t = " + seconds(t));
  next_time_event_ = update.next_event_time;
}

void ModelExchangeBlock::load(double t, std::span<const double> x, std::span<const double> u) const {
  fmu().set_time(t);
  if (!x.empty()) fmu().set_continuous_states(x);
  for (std::size_t i = 0; i < inputs_.size(); ++i) set_value(fmu(), *inputs_[i], u[i]);
}

void ModelExchangeBlock::initial_state(double, std::span<double> x) const {
  instantiate_now();
  std::copy(x0_.begin(), x0_.end(), x.begin());
}

void ModelExchangeBlock::derivatives(double t, std::span<const double> x, std::span<const double> u,
                                     std::span<double> dxdt) const {
  load(t, x, u);
  if (!dxdt.empty()) fmu().get_derivatives(dxdt);
}

void ModelExchangeBlock::calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                                      std::span<double> y) const {
  load(t, x, u);
  for (std::size_t i = 0; i < outputs_.size(); ++i) y[i] = get_value(fmu(), *outputs_[i]);
}

models::Crossing ModelExchangeBlock::event_direction(int index) const {
  return index == num_indicators_ ? models::Crossing::falling : models::Crossing::any;
}

void ModelExchangeBlock::event_functions(double t, std::span<const double> x, std::span<const double> u,
                                         std::span<double> g) const {
  if (num_indicators_ > 0) {
    load(t, x, u);
    fmu().get_event_indicators(g.first(static_cast<std::size_t>(num_indicators_)));
  }
  // Positive while the time event is ahead; none scheduled: a constant that never crosses.
  if (has_time_events_) g[static_cast<std::size_t>(num_indicators_)] = std::isfinite(next_time_event_) ? next_time_event_ - t : 1.0;
}

bool ModelExchangeBlock::handle_events(double t, std::span<double> x, std::span<const double> u,
                                       std::span<const int> crossed) {
  load(t, x, u);
  fmu().enter_event_mode();
  const DiscreteUpdate update = fmu().update_discrete_states();
  take_update(update, t);
  fmu().enter_continuous_time_mode();
  if (update.states_changed) fmu().get_continuous_states(x);
  // A time event moves the time function's zero: the integrator restarts its root finding.
  const bool time_event = has_time_events_ && crossed[static_cast<std::size_t>(num_indicators_)] != 0;
  return update.states_changed || time_event;
}

std::vector<double> ModelExchangeBlock::save_discrete_state() const {
  instantiate_now();
  std::vector<double> saved{std::isfinite(next_time_event_) ? 1.0 : 0.0,
                            std::isfinite(next_time_event_) ? next_time_event_ : 0.0};
  if (can_save_state_) append_bytes(saved, fmu().save_state());
  return saved;
}

void ModelExchangeBlock::restore_discrete_state(std::span<const double> saved) {
  std::vector<std::uint8_t> bytes;
  std::size_t used = 0;
  if (saved.size() < 2 || !read_bytes(saved.subspan(2), bytes, used) || 2 + used != saved.size()) {
    // An FMU without the flags saved no state: say what it lacks, else the record is damaged.
    if (!can_save_state_) fmu().restore_state({});
    throw FmuError(archive_->label(), "restore: the saved state is not one of this model-exchange block");
  }
  fmu().restore_state(bytes);
  next_time_event_ = saved[0] != 0.0 ? saved[1] : kNone;
}

}  // namespace mechsim::fmi
