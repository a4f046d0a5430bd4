// A Co-Simulation FMU as a models::Block: a sampled block with no continuous states, whose
// FMU steps itself (its own solver inside fmiXDoStep) on the block's sample grid. No new kind
// of block is needed: the sampled part of models::Block already runs a law on a grid
// t0 + k Ts with its inputs and outputs held in between (ZOH on both sides), which is what a
// co-simulation master does with an FMU. At each instant t_k (discrete_update):
//   1. k > 0: fmiXDoStep(t_{k-1}, Ts) with the inputs set at t_{k-1} (held over the step);
//   2. the inputs u(t_k) are set;
//   3. the outputs are read (after setting u(t_k): direct feedthrough is seen at t_k) and
//      held until t_{k+1}; calc_outputs returns them.
// This is the same sample-and-hold as the native sampled servo amplifier (servo_amplifier_block.h),
// so the servo amplifier FMU reproduces it (tests/unit/fmi).
//
// Ports as ModelExchangeBlock (the FMU's exchanged inputs and outputs, by name, with the
// FMU's units); outputs have no direct feedthrough (held). Errors: FmuError naming the FMU,
// participant, function and time (step status, NaN outputs, ...).
//
// Checkpoints (save/restore_discrete_state): the held outputs, the last sample instant and,
// for an FMU that declares canGetAndSetFMUstate and canSerializeFMUstate (FMI 3:
// ...FMUState), its serialized state, so that a rollback puts the FMU back where it was.
// Restoring into an FMU without those flags is refused (FmuError naming the missing flag);
// a run that may roll back refuses such an FMU before it starts. The step Ts is fixed: an
// adaptive macro step lands on the block's sample instants, as on a native sampled block's,
// so the FMU is always stepped by Ts.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/fmi/instance.h"
#include "mechsim/models/block.h"

namespace mechsim::fmi {

class LazyInstance;  // lazy_instance.h

class CoSimulationBlock final : public models::Block {
 public:
  // Instantiates (now or at first use: instantiation.h) the FMU of `archive` (shared: the unpacked folder lives as long as the block) for co-simulation,
  // sets `parameters` (name -> value in the FMU's unit) in initialization mode, initializes
  // it at t0, and steps it every `step_size` seconds (> 0).
  CoSimulationBlock(std::shared_ptr<const FmuArchive> archive, const std::map<std::string, double>& parameters, double t0,
                    double t_stop, double step_size);

  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  double sample_time() const override { return step_size_; }
  void discrete_update(double t, std::span<double> x, std::span<const double> u) override;
  std::vector<double> save_discrete_state() const override;
  void restore_discrete_state(std::span<const double> saved) override;
  // Loads, instantiates and initializes the FMU if it has not been yet (instantiation.h).
  void instantiate_now() const;
  const FmuArchive& archive() const { return *archive_; }
  ~CoSimulationBlock() override;

 private:
  FmuInstance& fmu() const;
  std::shared_ptr<const FmuArchive> archive_;
  std::unique_ptr<LazyInstance> fmu_;  // made now or at first use (instantiation.h)
  std::vector<const Variable*> inputs_, outputs_;
  double step_size_;
  bool can_save_state_ = false;  // canGetAndSetFMUstate and canSerializeFMUstate
  double last_sample_ = 0.0;
  bool sampled_once_ = false;
  mutable std::vector<double> held_;  // outputs at the last sample
};

}  // namespace mechsim::fmi
