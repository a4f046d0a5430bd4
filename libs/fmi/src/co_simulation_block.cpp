#include "mechsim/fmi/co_simulation_block.h"

#include "exchanged_variables.h"

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
  fmu_ = initialize(archive, InterfaceKind::co_simulation, parameters, t0, t_stop);
  held_.resize(outputs_.size());
  for (std::size_t i = 0; i < outputs_.size(); ++i) held_[i] = get_value(*fmu_, *outputs_[i]);
}

void CoSimulationBlock::calc_outputs(double, std::span<const double>, std::span<const double>,
                                     std::span<double> y) const {
  std::copy(held_.begin(), held_.end(), y.begin());
}

void CoSimulationBlock::discrete_update(double t, std::span<double>, std::span<const double> u) {
  if (sampled_once_ && t > last_sample_) fmu_->do_step(last_sample_, t - last_sample_);
  sampled_once_ = true;
  last_sample_ = t;
  for (std::size_t i = 0; i < inputs_.size(); ++i) set_value(*fmu_, *inputs_[i], u[i]);
  for (std::size_t i = 0; i < outputs_.size(); ++i) held_[i] = get_value(*fmu_, *outputs_[i]);
}

void CoSimulationBlock::restore_discrete_state(std::span<const double> saved) {
  // Only the held outputs: the FMU's own state is not restored (see the header).
  if (saved.size() != held_.size())
    throw FmuError(archive_->label(), "restore: expected " + std::to_string(held_.size()) + " held outputs");
  held_.assign(saved.begin(), saved.end());
}

}  // namespace mechsim::fmi
