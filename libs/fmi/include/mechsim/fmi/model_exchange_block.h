// A Model Exchange FMU as a models::Block: its continuous states, derivatives and event
// indicators come from the FMU, and mechsim's own SUNDIALS integrators (solve::BlockIntegrator)
// integrate it like any native block — in a node and in the monolithic composer alike.
//
// Ports: the FMU's Real/Float64 variables of causality input and output, by name, with the
// FMU's units (Integer/Int32 and Boolean inputs and outputs are carried as doubles). Each
// output depends directly on the inputs its <ModelStructure> dependencies list (on every
// input where the description does not say). States: the FMU's continuous states in its
// order, named after the variables their derivatives are declared for (state[i] where the
// description does not say).
//
// Events: the FMU's event indicators, either crossing direction, and (for an FMU with
// continuous states) one more event function for its time events, next_event_time - t,
// falling: the integrator lands on the time the FMU's last event iteration scheduled
// (nextEventTime), to its root-finding resolution, never before it. At either event the
// FMU's event iteration runs (enter event mode, update discrete states until settled) and
// may jump the states and schedule the next time event.
//
// Checkpoints (save/restore_discrete_state): the scheduled time event and, for an FMU that
// declares canGetAndSetFMUstate and canSerializeFMUstate (FMI 3: ...FMUState), its whole
// serialized state (discrete states, counters, whatever it keeps); the continuous states
// are the integrator's. Restoring into an FMU without those flags is refused (FmuError
// naming the missing flag): a run that may roll back refuses such an FMU before it starts.
//
// Refused (FmuError naming file, participant, function and time): every bad-FMU case of
// FmuInstance, a scene parameter the FMU lacks or that is not a parameter, a request to
// terminate, a time event of an FMU without continuous states (no integrator to land on
// it), NaN/inf outputs. fmi2CompletedIntegratorStep / fmi3CompletedIntegratorStep is not
// called (the integrator has no per-step hook): an FMU that needs it for step events is not
// run correctly.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/fmi/instance.h"
#include "mechsim/models/block.h"

namespace mechsim::fmi {

class LazyInstance;  // lazy_instance.h

class ModelExchangeBlock final : public models::Block {
 public:
  // Instantiates (now or at first use: instantiation.h) the FMU of `archive` (shared: the unpacked folder lives as long as the block) for model exchange,
  // sets `parameters` (name -> value in the FMU's unit) in initialization mode and
  // initializes it at t0.
  ModelExchangeBlock(std::shared_ptr<const FmuArchive> archive, const std::map<std::string, double>& parameters, double t0,
                     double t_stop);

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  int num_event_functions() const override { return num_indicators_ + (has_time_events_ ? 1 : 0); }
  models::Crossing event_direction(int index) const override;
  void event_functions(double t, std::span<const double> x, std::span<const double> u,
                       std::span<double> g) const override;
  bool handle_events(double t, std::span<double> x, std::span<const double> u,
                     std::span<const int> crossed) override;
  std::vector<double> save_discrete_state() const override;
  void restore_discrete_state(std::span<const double> saved) override;

  // The time event the FMU scheduled last (+inf: none).
  double next_time_event() const { return next_time_event_; }
  // Loads, instantiates and initializes the FMU if it has not been yet (instantiation.h).
  void instantiate_now() const;
  const FmuArchive& archive() const { return *archive_; }
  ~ModelExchangeBlock() override;

 private:
  FmuInstance& fmu() const;
  // Hands t, x and u to the FMU (the calls every evaluation starts with).
  void load(double t, std::span<const double> x, std::span<const double> u) const;
  // Ends an event iteration at t: refuses what the block cannot honour, keeps the next time event.
  void take_update(const DiscreteUpdate& update, double t) const;

  std::shared_ptr<const FmuArchive> archive_;
  std::unique_ptr<LazyInstance> fmu_;  // made now or at first use (instantiation.h)
  std::vector<const Variable*> inputs_, outputs_;
  mutable std::vector<double> x0_;
  int num_indicators_ = 0;
  bool has_time_events_ = false;  // the event function of the FMU's time events (always: with states or without)
  bool can_save_state_ = false;   // canGetAndSetFMUstate and canSerializeFMUstate
  mutable double next_time_event_;
};

}  // namespace mechsim::fmi
