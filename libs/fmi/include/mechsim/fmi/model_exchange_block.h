// A Model Exchange FMU as a models::Block: its continuous states, derivatives and event
// indicators come from the FMU, and mechsim's own SUNDIALS integrators (solve::BlockIntegrator)
// integrate it like any native block — in a node and in the monolithic composer alike.
//
// Ports: the FMU's Real/Float64 variables of causality input and output, by name, with the
// FMU's units (Integer/Int32 and Boolean inputs and outputs are carried as doubles). States:
// the FMU's continuous states in its order, named after the variables their derivatives
// are declared for (state[i] where the description does not say). Events: the
// FMU's event indicators, either crossing direction; at a crossing the FMU's event iteration
// runs (enter event mode, update discrete states until settled) and may jump the states.
//
// Each output is declared as depending directly on every input (the conservative reading of
// a description without dependencies; <ModelStructure> dependencies are not read yet).
// Refused (FmuError naming file, participant, function and time): every bad-FMU case of
// FmuInstance, a scene parameter the FMU lacks or that is not a parameter, an FMU that asks
// for time events (nextEventTime: not supported yet) or to terminate, NaN/inf outputs.
// fmi2CompletedIntegratorStep / fmi3CompletedIntegratorStep is not called (the integrator
// has no per-step hook): an FMU that needs it for step events is not run correctly.
// Checkpoints hold the continuous states only (the FMU's discrete state, e.g. a counter, is
// not saved): a rollback of an FMU with discrete state is not supported yet.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/fmi/instance.h"
#include "mechsim/models/block.h"

namespace mechsim::fmi {

class ModelExchangeBlock final : public models::Block {
 public:
  // Instantiates the FMU of `archive` (shared: the unpacked folder lives as long as the block) for model exchange,
  // sets `parameters` (name -> value in the FMU's unit) in initialization mode and
  // initializes it at t0.
  ModelExchangeBlock(std::shared_ptr<const FmuArchive> archive, const std::map<std::string, double>& parameters, double t0,
                     double t_stop);

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  int num_event_functions() const override { return num_indicators_; }
  void event_functions(double t, std::span<const double> x, std::span<const double> u,
                       std::span<double> g) const override;
  bool handle_events(double t, std::span<double> x, std::span<const double> u,
                     std::span<const int> crossed) override;

 private:
  // Hands t, x and u to the FMU (the calls every evaluation starts with).
  void load(double t, std::span<const double> x, std::span<const double> u) const;

  std::shared_ptr<const FmuArchive> archive_;
  std::unique_ptr<FmuInstance> fmu_;
  std::vector<const Variable*> inputs_, outputs_;
  std::vector<double> x0_;
  int num_indicators_ = 0;
};

}  // namespace mechsim::fmi
