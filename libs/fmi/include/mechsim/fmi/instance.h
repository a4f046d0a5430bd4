// One instance of an FMU's binary, FMI 2 or 3 behind the same calls: the binary is loaded
// with dlopen, every function mechsim calls for the chosen interface is resolved up front
// (a missing one is refused by name), and every call's status is checked: a status of
// discard, error or fatal throws FmuError naming the FMU, the participant, the function and
// the time. Messages the FMU logs are kept and appended to that error.
//
// Call order (the standard's state machines, both versions):
//   enter_initialization(t0) -> set/get start values, parameters -> exit_initialization()
//   co-simulation:  { set inputs -> do_step(t, h) -> get outputs }*
//   model exchange: event mode after exit_initialization: update_discrete_states() until
//                   settled, enter_continuous_time_mode(), then { set_time, set_states,
//                   derivatives / event_indicators, completed_integrator_step }*, with
//                   enter_event_mode() + update_discrete_states() at each event.
//   terminate() (the destructor frees the instance either way).
#pragma once

#include <cstdint>
#include <utility>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mechsim/fmi/archive.h"

namespace mechsim::fmi {

// The outcome of an event iteration (fmi2NewDiscreteStates / fmi3UpdateDiscreteStates,
// repeated until the FMU asks for no further one).
struct DiscreteUpdate {
  bool states_changed = false;      // valuesOfContinuousStatesChanged: re-read the states
  bool terminate = false;           // the FMU asks to end the simulation
  bool next_event_time_defined = false;
  double next_event_time = 0.0;
};

// What an FMU lacks for mechsim to save and restore its state (checkpoints, rollback): ""
// when its interface `kind` declares both flags, else the missing ones as the FMU's version
// spells them ("canSerializeFMUstate", "canGetAndSetFMUState and canSerializeFMUState").
std::string missing_state_capabilities(const ModelDescription& md, InterfaceKind kind);

class FmuInstance {
 public:
  // Loads the binary of `kind` from the archive (which must outlive the instance) and
  // instantiates it under `instance_name`. Refuses an interface the FMU lacks, no binary
  // for this platform, a binary that does not load, a missing function and an instantiate
  // that returns NULL.
  static std::unique_ptr<FmuInstance> create(const FmuArchive& archive, InterfaceKind kind,
                                             const std::string& instance_name);
  virtual ~FmuInstance() = default;
  FmuInstance(const FmuInstance&) = delete;
  FmuInstance& operator=(const FmuInstance&) = delete;

  InterfaceKind kind() const { return kind_; }
  const FmuLabel& label() const { return label_; }

  virtual void enter_initialization(double start_time, double stop_time) = 0;
  virtual void exit_initialization() = 0;
  virtual void terminate() = 0;

  virtual double get_real(std::uint32_t vr) = 0;
  virtual void set_real(std::uint32_t vr, double value) = 0;
  virtual std::int32_t get_integer(std::uint32_t vr) = 0;
  virtual void set_integer(std::uint32_t vr, std::int32_t value) = 0;
  virtual bool get_boolean(std::uint32_t vr) = 0;
  virtual void set_boolean(std::uint32_t vr, bool value) = 0;

  // get_real of an output, refused when it is NaN or infinite (naming the variable and the
  // time of the last step or set_time).
  double get_finite_real(const Variable& v);

  // --- co-simulation ---
  virtual void do_step(double t, double h) = 0;

  // --- model exchange ---
  virtual void set_time(double t) = 0;
  virtual void set_continuous_states(std::span<const double> x) = 0;
  virtual void get_continuous_states(std::span<double> x) = 0;
  virtual void get_derivatives(std::span<double> dxdt) = 0;
  virtual void get_event_indicators(std::span<double> z) = 0;
  virtual void enter_event_mode() = 0;
  virtual DiscreteUpdate update_discrete_states() = 0;  // iterates until settled
  virtual void enter_continuous_time_mode() = 0;
  // Returns true when the FMU asks for event mode (a step event).
  virtual bool completed_integrator_step() = 0;

  // --- FMU state (both interfaces; needs canGetAndSetFMUstate and canSerializeFMUstate) ---
  // The FMU's whole state as bytes (fmiXGetFMUstate, SerializedFMUstateSize, Serialize,
  // FreeFMUstate), and back into this or another instance of the same FMU (DeSerialize,
  // SetFMUstate, FreeFMUstate): what a checkpoint holds of an FMU. The functions are
  // resolved at load only when the description declares both flags; without them these
  // throw FmuError naming the missing flag.
  virtual std::vector<std::uint8_t> save_state() = 0;
  virtual void restore_state(std::span<const std::uint8_t> bytes) = 0;

 protected:
  FmuInstance(FmuLabel label, InterfaceKind kind) : label_(std::move(label)), kind_(kind) {}
  // Throws FmuError when missing_state_ is not empty (a save or restore without the flags).
  void require_state_capability(const char* what) const;
  FmuLabel label_;
  InterfaceKind kind_;
  std::string missing_state_;  // missing_state_capabilities of the description
  // Once a state was saved (or set) it may be set again later (a rollback): the steps then tell the
  // FMU that a state prior to their start may still be set (noSetFMUStatePriorToCurrentPoint
  // false), so that it keeps what such a set needs.
  bool state_saved_ = false;
  double time_ = 0.0;  // the FMU's time: after the last step, set_time or initialization
};

}  // namespace mechsim::fmi
