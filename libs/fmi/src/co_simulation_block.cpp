#include "mechsim/fmi/co_simulation_block.h"

#include "exchanged_variables.h"
#include "lazy_instance.h"
#include "saved_state.h"

namespace mechsim::fmi {

CoSimulationBlock::CoSimulationBlock(std::shared_ptr<const FmuArchive> archive_in, const std::map<std::string, double>& parameters,
                                     double t0, double t_stop, double step_size)
    : Block("fmu"), archive_(std::move(archive_in)), step_size_(step_size), last_sample_(t0) {
  const FmuArchive& archive = *archive_;
  if (!(step_size > 0))
    throw FmuError(archive.label(), "the co-simulation step must be > 0 s (got " + std::to_string(step_size) + ")");
  const ExchangedVariables ports = exchanged_variables(archive.description());
  inputs_ = ports.inputs;
  outputs_ = ports.outputs;
  for (const Variable* v : inputs_) declare_input(v->name, port_unit(*v), start_value(*v, archive.label()));
  for (const Variable* v : outputs_) declare_output(v->name, port_unit(*v));  // held: no feedthrough
  can_save_state_ = missing_state_capabilities(archive.description(), InterfaceKind::co_simulation).empty();
  held_.resize(outputs_.size());
  fmu_ = std::make_unique<LazyInstance>(
      [this, parameters, t0, t_stop] { return initialize(*archive_, InterfaceKind::co_simulation, parameters, t0, t_stop); },
      [this](FmuInstance& fmu) {
        for (std::size_t i = 0; i < outputs_.size(); ++i) held_[i] = get_value(fmu, *outputs_[i]);
      });
  fmu_->make_unless_deferred();
}

CoSimulationBlock::~CoSimulationBlock() = default;
void CoSimulationBlock::instantiate_now() const { fmu_->get(); }
FmuInstance& CoSimulationBlock::fmu() const { return fmu_->get(); }

void CoSimulationBlock::calc_outputs(double, std::span<const double>, std::span<const double>,
                                     std::span<double> y) const {
  instantiate_now();
  std::copy(held_.begin(), held_.end(), y.begin());
}

void CoSimulationBlock::discrete_update(double t, std::span<double>, std::span<const double> u) {
  if (sampled_once_ && t > last_sample_) fmu().do_step(last_sample_, t - last_sample_);
  sampled_once_ = true;
  last_sample_ = t;
  for (std::size_t i = 0; i < inputs_.size(); ++i) set_value(fmu(), *inputs_[i], u[i]);
  for (std::size_t i = 0; i < outputs_.size(); ++i) held_[i] = get_value(fmu(), *outputs_[i]);
}

// Layout: the held outputs, sampled_once, the last sample instant, then the FMU's bytes.
std::vector<double> CoSimulationBlock::save_discrete_state() const {
  instantiate_now();
  std::vector<double> saved = held_;
  saved.push_back(sampled_once_ ? 1.0 : 0.0);
  saved.push_back(last_sample_);
  if (can_save_state_) append_bytes(saved, fmu().save_state());
  return saved;
}

void CoSimulationBlock::restore_discrete_state(std::span<const double> saved) {
  const std::size_t n = held_.size();
  std::vector<std::uint8_t> bytes;
  std::size_t used = 0;
  if (saved.size() < n + 2 || !read_bytes(saved.subspan(n + 2), bytes, used) || n + 2 + used != saved.size()) {
    // An FMU without the flags saved no state: say what it lacks, else the record is damaged.
    if (!can_save_state_) fmu().restore_state({});
    throw FmuError(archive_->label(), "restore: the saved state is not one of this co-simulation block");
  }
  fmu().restore_state(bytes);
  held_.assign(saved.begin(), saved.begin() + static_cast<std::ptrdiff_t>(n));
  sampled_once_ = saved[n] != 0.0;
  last_sample_ = saved[n + 1];
}

}  // namespace mechsim::fmi
