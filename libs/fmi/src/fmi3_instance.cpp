// FmuInstance over the FMI 3.0 C API.
#include "mechsim/fmi/fmi3_functions.h"
#include "shared_library.h"
#include "versioned_instances.h"
#include "call_log.h"

namespace mechsim::fmi {

namespace {

const char* status_name(fmi3Status s) {
  switch (s) {
    case fmi3OK: return "fmi3OK";
    case fmi3Warning: return "fmi3Warning";
    case fmi3Discard: return "fmi3Discard";
    case fmi3Error: return "fmi3Error";
    case fmi3Fatal: return "fmi3Fatal";
  }
  return "an unknown fmi3Status";
}

void log_message(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category, fmi3String message) {
  static_cast<CallLog*>(environment)->add_message(status_name(status), category ? category : "",
                                                  message ? message : "");
}

class Fmi3Instance final : public FmuInstance {
 public:
  Fmi3Instance(const FmuArchive& archive, InterfaceKind kind, const std::string& instance_name)
      : FmuInstance(archive.label(), kind),
        log_(archive.label()),
        library_(archive.binary_path(kind),
                 "binaries/" + host_platform(FmiVersion::fmi3) + "/" +
                     archive.require_interface(kind).model_identifier + ".so",
                 archive.label()) {
    const std::string common = "FMI 3.0";
    const bool cs = kind == InterfaceKind::co_simulation;
    const std::string own = cs ? "FMI 3.0 co-simulation" : "FMI 3.0 model exchange";
    free_instance_ = library_.function<fmi3FreeInstanceTYPE>("fmi3FreeInstance", common);
    enter_init_ = library_.function<fmi3EnterInitializationModeTYPE>("fmi3EnterInitializationMode", common);
    exit_init_ = library_.function<fmi3ExitInitializationModeTYPE>("fmi3ExitInitializationMode", common);
    terminate_ = library_.function<fmi3TerminateTYPE>("fmi3Terminate", common);
    get_float64_ = library_.function<fmi3GetFloat64TYPE>("fmi3GetFloat64", common);
    set_float64_ = library_.function<fmi3SetFloat64TYPE>("fmi3SetFloat64", common);
    get_int32_ = library_.function<fmi3GetInt32TYPE>("fmi3GetInt32", common);
    set_int32_ = library_.function<fmi3SetInt32TYPE>("fmi3SetInt32", common);
    get_boolean_ = library_.function<fmi3GetBooleanTYPE>("fmi3GetBoolean", common);
    set_boolean_ = library_.function<fmi3SetBooleanTYPE>("fmi3SetBoolean", common);
    missing_state_ = missing_state_capabilities(archive.description(), kind);
    if (missing_state_.empty()) {
      const std::string state = "FMI 3.0 FMU state (the FMU declares canGetAndSetFMUState and canSerializeFMUState)";
      get_state_ = library_.function<fmi3GetFMUStateTYPE>("fmi3GetFMUState", state);
      set_state_ = library_.function<fmi3SetFMUStateTYPE>("fmi3SetFMUState", state);
      free_state_ = library_.function<fmi3FreeFMUStateTYPE>("fmi3FreeFMUState", state);
      state_size_ = library_.function<fmi3SerializedFMUStateSizeTYPE>("fmi3SerializedFMUStateSize", state);
      serialize_ = library_.function<fmi3SerializeFMUStateTYPE>("fmi3SerializeFMUState", state);
      deserialize_ = library_.function<fmi3DeserializeFMUStateTYPE>("fmi3DeserializeFMUState", state);
    }
    const std::string token = archive.description().instantiation_token;
    const std::string resources = archive.resource_location();
    if (cs) {
      auto* instantiate = library_.function<fmi3InstantiateCoSimulationTYPE>("fmi3InstantiateCoSimulation", own);
      do_step_ = library_.function<fmi3DoStepTYPE>("fmi3DoStep", own);
      // No event mode, no early return, no intermediate variables: a plain step per call.
      instance_ = instantiate(instance_name.c_str(), token.c_str(), resources.c_str(), false, false, false, false,
                              nullptr, 0, &log_, log_message, nullptr);
      if (instance_ == nullptr) log_.fail_at_setup("fmi3InstantiateCoSimulation returned NULL (the FMU refused to instantiate)");
    } else {
      auto* instantiate = library_.function<fmi3InstantiateModelExchangeTYPE>("fmi3InstantiateModelExchange", own);
      enter_event_mode_ = library_.function<fmi3EnterEventModeTYPE>("fmi3EnterEventMode", own);
      update_discrete_ = library_.function<fmi3UpdateDiscreteStatesTYPE>("fmi3UpdateDiscreteStates", own);
      enter_ct_mode_ = library_.function<fmi3EnterContinuousTimeModeTYPE>("fmi3EnterContinuousTimeMode", own);
      completed_step_ = library_.function<fmi3CompletedIntegratorStepTYPE>("fmi3CompletedIntegratorStep", own);
      set_time_ = library_.function<fmi3SetTimeTYPE>("fmi3SetTime", own);
      set_states_ = library_.function<fmi3SetContinuousStatesTYPE>("fmi3SetContinuousStates", own);
      get_states_ = library_.function<fmi3GetContinuousStatesTYPE>("fmi3GetContinuousStates", own);
      get_derivatives_ =
          library_.function<fmi3GetContinuousStateDerivativesTYPE>("fmi3GetContinuousStateDerivatives", own);
      get_indicators_ = library_.function<fmi3GetEventIndicatorsTYPE>("fmi3GetEventIndicators", own);
      instance_ = instantiate(instance_name.c_str(), token.c_str(), resources.c_str(), false, false, &log_,
                              log_message);
      if (instance_ == nullptr) log_.fail_at_setup("fmi3InstantiateModelExchange returned NULL (the FMU refused to instantiate)");
    }
  }

  ~Fmi3Instance() override {
    if (instance_ != nullptr) free_instance_(instance_);
  }

  void enter_initialization(double start_time, double stop_time) override {
    time_ = start_time;
    log_.set_time(start_time);
    check("fmi3EnterInitializationMode", enter_init_(instance_, false, 0.0, start_time, true, stop_time));
  }
  void exit_initialization() override { check("fmi3ExitInitializationMode", exit_init_(instance_)); }
  void terminate() override { check("fmi3Terminate", terminate_(instance_)); }

  double get_real(std::uint32_t vr) override {
    fmi3Float64 v = 0;
    check("fmi3GetFloat64", get_float64_(instance_, &vr, 1, &v, 1));
    return v;
  }
  void set_real(std::uint32_t vr, double value) override {
    check("fmi3SetFloat64", set_float64_(instance_, &vr, 1, &value, 1));
  }
  std::int32_t get_integer(std::uint32_t vr) override {
    fmi3Int32 v = 0;
    check("fmi3GetInt32", get_int32_(instance_, &vr, 1, &v, 1));
    return v;
  }
  void set_integer(std::uint32_t vr, std::int32_t value) override {
    check("fmi3SetInt32", set_int32_(instance_, &vr, 1, &value, 1));
  }
  bool get_boolean(std::uint32_t vr) override {
    fmi3Boolean v = false;
    check("fmi3GetBoolean", get_boolean_(instance_, &vr, 1, &v, 1));
    return v;
  }
  void set_boolean(std::uint32_t vr, bool value) override {
    const fmi3Boolean v = value;
    check("fmi3SetBoolean", set_boolean_(instance_, &vr, 1, &v, 1));
  }

  void do_step(double t, double h) override {
    log_.set_time(t);
    fmi3Boolean event_needed = false, terminate = false, early_return = false;
    fmi3Float64 last_time = t;
    check("fmi3DoStep", do_step_(instance_, t, h, !state_saved_, &event_needed, &terminate, &early_return, &last_time));
    // Early return was not allowed at instantiation; an FMU that still stops short broke
    // the contract, and its outputs are not at t + h.
    if (early_return) log_.fail("fmi3DoStep", "an early return at t = " + std::to_string(last_time) + " s (not allowed)");
    time_ = t + h;
  }

  void set_time(double t) override {
    time_ = t;
    log_.set_time(t);
    check("fmi3SetTime", set_time_(instance_, t));
  }
  void set_continuous_states(std::span<const double> x) override {
    check("fmi3SetContinuousStates", set_states_(instance_, x.data(), x.size()));
  }
  void get_continuous_states(std::span<double> x) override {
    check("fmi3GetContinuousStates", get_states_(instance_, x.data(), x.size()));
  }
  void get_derivatives(std::span<double> dxdt) override {
    check("fmi3GetContinuousStateDerivatives", get_derivatives_(instance_, dxdt.data(), dxdt.size()));
  }
  void get_event_indicators(std::span<double> z) override {
    check("fmi3GetEventIndicators", get_indicators_(instance_, z.data(), z.size()));
  }
  void enter_event_mode() override { check("fmi3EnterEventMode", enter_event_mode_(instance_)); }
  DiscreteUpdate update_discrete_states() override {
    DiscreteUpdate out;
    fmi3Boolean need_update = true, terminate = false, nominals_changed = false, values_changed = false,
                next_defined = false;
    fmi3Float64 next_time = 0.0;
    while (need_update && !terminate) {
      check("fmi3UpdateDiscreteStates", update_discrete_(instance_, &need_update, &terminate, &nominals_changed,
                                                         &values_changed, &next_defined, &next_time));
      out.states_changed = out.states_changed || values_changed;
    }
    out.terminate = terminate;
    out.next_event_time_defined = next_defined;
    out.next_event_time = next_time;
    return out;
  }
  void enter_continuous_time_mode() override {
    check("fmi3EnterContinuousTimeMode", enter_ct_mode_(instance_));
  }
  bool completed_integrator_step() override {
    fmi3Boolean enter_event = false, terminate = false;
    check("fmi3CompletedIntegratorStep", completed_step_(instance_, !state_saved_, &enter_event, &terminate));
    return enter_event;
  }

  std::vector<std::uint8_t> save_state() override {
    require_state_capability("save");
    fmi3FMUState state = nullptr;
    check("fmi3GetFMUState", get_state_(instance_, &state));
    const StateGuard guard{this, state};
    std::size_t size = 0;
    check("fmi3SerializedFMUStateSize", state_size_(instance_, state, &size));
    std::vector<std::uint8_t> bytes(size);
    check("fmi3SerializeFMUState", serialize_(instance_, state, bytes.data(), size));
    state_saved_ = true;
    return bytes;
  }
  void restore_state(std::span<const std::uint8_t> bytes) override {
    require_state_capability("restore");
    fmi3FMUState state = nullptr;
    check("fmi3DeserializeFMUState", deserialize_(instance_, bytes.data(), bytes.size(), &state));
    const StateGuard guard{this, state};
    check("fmi3SetFMUState", set_state_(instance_, state));
    state_saved_ = true;  // it may be set again (a second rollback to the same checkpoint)
  }

 private:
  // Frees an FMU state however the call that used it ended.
  struct StateGuard {
    Fmi3Instance* self;
    fmi3FMUState state;
    ~StateGuard() {
      if (state != nullptr) self->free_state_(self->instance_, &state);
    }
  };
  void check(const char* function, fmi3Status status) const {
    if (status == fmi3OK || status == fmi3Warning) return;
    log_.fail(function, status_name(status));
  }

  CallLog log_;  // first: the logger's environment, alive while the instance is
  SharedLibrary library_;
  fmi3Instance instance_ = nullptr;
  fmi3FreeInstanceTYPE* free_instance_ = nullptr;
  fmi3EnterInitializationModeTYPE* enter_init_ = nullptr;
  fmi3ExitInitializationModeTYPE* exit_init_ = nullptr;
  fmi3TerminateTYPE* terminate_ = nullptr;
  fmi3GetFloat64TYPE* get_float64_ = nullptr;
  fmi3SetFloat64TYPE* set_float64_ = nullptr;
  fmi3GetInt32TYPE* get_int32_ = nullptr;
  fmi3SetInt32TYPE* set_int32_ = nullptr;
  fmi3GetBooleanTYPE* get_boolean_ = nullptr;
  fmi3SetBooleanTYPE* set_boolean_ = nullptr;
  fmi3DoStepTYPE* do_step_ = nullptr;
  fmi3EnterEventModeTYPE* enter_event_mode_ = nullptr;
  fmi3UpdateDiscreteStatesTYPE* update_discrete_ = nullptr;
  fmi3EnterContinuousTimeModeTYPE* enter_ct_mode_ = nullptr;
  fmi3CompletedIntegratorStepTYPE* completed_step_ = nullptr;
  fmi3SetTimeTYPE* set_time_ = nullptr;
  fmi3SetContinuousStatesTYPE* set_states_ = nullptr;
  fmi3GetContinuousStatesTYPE* get_states_ = nullptr;
  fmi3GetContinuousStateDerivativesTYPE* get_derivatives_ = nullptr;
  fmi3GetEventIndicatorsTYPE* get_indicators_ = nullptr;
  fmi3GetFMUStateTYPE* get_state_ = nullptr;
  fmi3SetFMUStateTYPE* set_state_ = nullptr;
  fmi3FreeFMUStateTYPE* free_state_ = nullptr;
  fmi3SerializedFMUStateSizeTYPE* state_size_ = nullptr;
  fmi3SerializeFMUStateTYPE* serialize_ = nullptr;
  fmi3DeserializeFMUStateTYPE* deserialize_ = nullptr;
};

}  // namespace

std::unique_ptr<FmuInstance> make_fmi3_instance(const FmuArchive& archive, InterfaceKind kind,
                                                const std::string& instance_name) {
  return std::make_unique<Fmi3Instance>(archive, kind, instance_name);
}

}  // namespace mechsim::fmi
