// FmuInstance over the FMI 2.0 C API.
#include "versioned_instances.h"
#include "call_log.h"

#include <cstdarg>
#include <cstdio>
#include <cstdlib>

#include "mechsim/fmi/fmi2_functions.h"
#include "shared_library.h"

namespace mechsim::fmi {

namespace {

const char* status_name(fmi2Status s) {
  switch (s) {
    case fmi2OK: return "fmi2OK";
    case fmi2Warning: return "fmi2Warning";
    case fmi2Discard: return "fmi2Discard";
    case fmi2Error: return "fmi2Error";
    case fmi2Fatal: return "fmi2Fatal";
    case fmi2Pending: return "fmi2Pending";
  }
  return "an unknown fmi2Status";
}

// The logger hands printf-style messages; the environment is the instance's CallLog.
void log_message(fmi2ComponentEnvironment environment, fmi2String, fmi2Status status, fmi2String category,
                 fmi2String message, ...) {
  char text[1024];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message ? message : "", args);
  va_end(args);
  static_cast<CallLog*>(environment)->add_message(status_name(status), category ? category : "", text);
}

class Fmi2Instance final : public FmuInstance {
 public:
  Fmi2Instance(const FmuArchive& archive, InterfaceKind kind, const std::string& instance_name)
      : FmuInstance(archive.label(), kind),
        log_(archive.label()),
        library_(archive.binary_path(kind),
                 "binaries/" + host_platform(FmiVersion::fmi2) + "/" +
                     archive.require_interface(kind).model_identifier + ".so",
                 archive.label()) {
    const std::string common = "FMI 2.0";
    const std::string own = kind == InterfaceKind::co_simulation ? "FMI 2.0 co-simulation" : "FMI 2.0 model exchange";
    instantiate_ = library_.function<fmi2InstantiateTYPE>("fmi2Instantiate", common);
    free_instance_ = library_.function<fmi2FreeInstanceTYPE>("fmi2FreeInstance", common);
    setup_experiment_ = library_.function<fmi2SetupExperimentTYPE>("fmi2SetupExperiment", common);
    enter_init_ = library_.function<fmi2EnterInitializationModeTYPE>("fmi2EnterInitializationMode", common);
    exit_init_ = library_.function<fmi2ExitInitializationModeTYPE>("fmi2ExitInitializationMode", common);
    terminate_ = library_.function<fmi2TerminateTYPE>("fmi2Terminate", common);
    get_real_ = library_.function<fmi2GetRealTYPE>("fmi2GetReal", common);
    set_real_ = library_.function<fmi2SetRealTYPE>("fmi2SetReal", common);
    get_integer_ = library_.function<fmi2GetIntegerTYPE>("fmi2GetInteger", common);
    set_integer_ = library_.function<fmi2SetIntegerTYPE>("fmi2SetInteger", common);
    get_boolean_ = library_.function<fmi2GetBooleanTYPE>("fmi2GetBoolean", common);
    set_boolean_ = library_.function<fmi2SetBooleanTYPE>("fmi2SetBoolean", common);
    if (kind == InterfaceKind::co_simulation) {
      do_step_ = library_.function<fmi2DoStepTYPE>("fmi2DoStep", own);
    } else {
      enter_event_mode_ = library_.function<fmi2EnterEventModeTYPE>("fmi2EnterEventMode", own);
      new_discrete_states_ = library_.function<fmi2NewDiscreteStatesTYPE>("fmi2NewDiscreteStates", own);
      enter_ct_mode_ = library_.function<fmi2EnterContinuousTimeModeTYPE>("fmi2EnterContinuousTimeMode", own);
      completed_step_ = library_.function<fmi2CompletedIntegratorStepTYPE>("fmi2CompletedIntegratorStep", own);
      set_time_ = library_.function<fmi2SetTimeTYPE>("fmi2SetTime", own);
      set_states_ = library_.function<fmi2SetContinuousStatesTYPE>("fmi2SetContinuousStates", own);
      get_states_ = library_.function<fmi2GetContinuousStatesTYPE>("fmi2GetContinuousStates", own);
      get_derivatives_ = library_.function<fmi2GetDerivativesTYPE>("fmi2GetDerivatives", own);
      get_indicators_ = library_.function<fmi2GetEventIndicatorsTYPE>("fmi2GetEventIndicators", own);
    }
    missing_state_ = missing_state_capabilities(archive.description(), kind);
    if (missing_state_.empty()) {
      const std::string state = "FMI 2.0 FMU state (the FMU declares canGetAndSetFMUstate and canSerializeFMUstate)";
      get_state_ = library_.function<fmi2GetFMUstateTYPE>("fmi2GetFMUstate", state);
      set_state_ = library_.function<fmi2SetFMUstateTYPE>("fmi2SetFMUstate", state);
      free_state_ = library_.function<fmi2FreeFMUstateTYPE>("fmi2FreeFMUstate", state);
      state_size_ = library_.function<fmi2SerializedFMUstateSizeTYPE>("fmi2SerializedFMUstateSize", state);
      serialize_ = library_.function<fmi2SerializeFMUstateTYPE>("fmi2SerializeFMUstate", state);
      deserialize_ = library_.function<fmi2DeSerializeFMUstateTYPE>("fmi2DeSerializeFMUstate", state);
    }
    callbacks_ = {log_message, std::calloc, std::free, nullptr, &log_};
    const std::string resources = archive.resource_location();
    component_ = instantiate_(instance_name.c_str(),
                              kind == InterfaceKind::co_simulation ? fmi2CoSimulation : fmi2ModelExchange,
                              archive.description().instantiation_token.c_str(), resources.c_str(), &callbacks_,
                              fmi2False, fmi2False);
    if (component_ == nullptr) log_.fail_at_setup("fmi2Instantiate returned NULL (the FMU refused to instantiate)");
  }

  ~Fmi2Instance() override {
    if (component_ != nullptr) free_instance_(component_);
  }

  void enter_initialization(double start_time, double stop_time) override {
    time_ = start_time;
    log_.set_time(start_time);
    check("fmi2SetupExperiment", setup_experiment_(component_, fmi2False, 0.0, start_time, fmi2True, stop_time));
    check("fmi2EnterInitializationMode", enter_init_(component_));
  }
  void exit_initialization() override { check("fmi2ExitInitializationMode", exit_init_(component_)); }
  void terminate() override { check("fmi2Terminate", terminate_(component_)); }

  double get_real(std::uint32_t vr) override {
    fmi2Real v = 0;
    check("fmi2GetReal", get_real_(component_, &vr, 1, &v));
    return v;
  }
  void set_real(std::uint32_t vr, double value) override { check("fmi2SetReal", set_real_(component_, &vr, 1, &value)); }
  std::int32_t get_integer(std::uint32_t vr) override {
    fmi2Integer v = 0;
    check("fmi2GetInteger", get_integer_(component_, &vr, 1, &v));
    return v;
  }
  void set_integer(std::uint32_t vr, std::int32_t value) override {
    const fmi2Integer v = value;
    check("fmi2SetInteger", set_integer_(component_, &vr, 1, &v));
  }
  bool get_boolean(std::uint32_t vr) override {
    fmi2Boolean v = fmi2False;
    check("fmi2GetBoolean", get_boolean_(component_, &vr, 1, &v));
    return v != fmi2False;
  }
  void set_boolean(std::uint32_t vr, bool value) override {
    const fmi2Boolean v = value ? fmi2True : fmi2False;
    check("fmi2SetBoolean", set_boolean_(component_, &vr, 1, &v));
  }

  void do_step(double t, double h) override {
    log_.set_time(t);
    check("fmi2DoStep", do_step_(component_, t, h, state_saved_ ? fmi2False : fmi2True));
    time_ = t + h;
  }

  void set_time(double t) override {
    time_ = t;
    log_.set_time(t);
    check("fmi2SetTime", set_time_(component_, t));
  }
  void set_continuous_states(std::span<const double> x) override {
    check("fmi2SetContinuousStates", set_states_(component_, x.data(), x.size()));
  }
  void get_continuous_states(std::span<double> x) override {
    check("fmi2GetContinuousStates", get_states_(component_, x.data(), x.size()));
  }
  void get_derivatives(std::span<double> dxdt) override {
    check("fmi2GetDerivatives", get_derivatives_(component_, dxdt.data(), dxdt.size()));
  }
  void get_event_indicators(std::span<double> z) override {
    check("fmi2GetEventIndicators", get_indicators_(component_, z.data(), z.size()));
  }
  void enter_event_mode() override { check("fmi2EnterEventMode", enter_event_mode_(component_)); }
  DiscreteUpdate update_discrete_states() override {
    DiscreteUpdate out;
    fmi2EventInfo info{fmi2True, fmi2False, fmi2False, fmi2False, fmi2False, 0.0};
    while (info.newDiscreteStatesNeeded != fmi2False && info.terminateSimulation == fmi2False) {
      check("fmi2NewDiscreteStates", new_discrete_states_(component_, &info));
      out.states_changed = out.states_changed || info.valuesOfContinuousStatesChanged != fmi2False;
    }
    out.terminate = info.terminateSimulation != fmi2False;
    out.next_event_time_defined = info.nextEventTimeDefined != fmi2False;
    out.next_event_time = info.nextEventTime;
    return out;
  }
  void enter_continuous_time_mode() override {
    check("fmi2EnterContinuousTimeMode", enter_ct_mode_(component_));
  }
  bool completed_integrator_step() override {
    fmi2Boolean enter_event = fmi2False, terminate = fmi2False;
    check("fmi2CompletedIntegratorStep",
          completed_step_(component_, state_saved_ ? fmi2False : fmi2True, &enter_event, &terminate));
    return enter_event != fmi2False;
  }

  std::vector<std::uint8_t> save_state() override {
    require_state_capability("save");
    fmi2FMUstate state = nullptr;
    check("fmi2GetFMUstate", get_state_(component_, &state));
    const StateGuard guard{this, state};
    std::size_t size = 0;
    check("fmi2SerializedFMUstateSize", state_size_(component_, state, &size));
    std::vector<std::uint8_t> bytes(size);
    check("fmi2SerializeFMUstate", serialize_(component_, state, reinterpret_cast<fmi2Byte*>(bytes.data()), size));
    state_saved_ = true;
    return bytes;
  }
  void restore_state(std::span<const std::uint8_t> bytes) override {
    require_state_capability("restore");
    fmi2FMUstate state = nullptr;
    check("fmi2DeSerializeFMUstate",
          deserialize_(component_, reinterpret_cast<const fmi2Byte*>(bytes.data()), bytes.size(), &state));
    const StateGuard guard{this, state};
    check("fmi2SetFMUstate", set_state_(component_, state));
    state_saved_ = true;  // it may be set again (a second rollback to the same checkpoint)
  }

 private:
  // Frees an FMU state however the call that used it ended.
  struct StateGuard {
    Fmi2Instance* self;
    fmi2FMUstate state;
    ~StateGuard() {
      if (state != nullptr) self->free_state_(self->component_, &state);
    }
  };
  void check(const char* function, fmi2Status status) const {
    if (status == fmi2OK || status == fmi2Warning) return;
    log_.fail(function, status_name(status));
  }

  CallLog log_;  // first: the logger's environment, alive while the component is
  SharedLibrary library_;
  fmi2CallbackFunctions callbacks_{};
  fmi2Component component_ = nullptr;
  fmi2InstantiateTYPE* instantiate_ = nullptr;
  fmi2FreeInstanceTYPE* free_instance_ = nullptr;
  fmi2SetupExperimentTYPE* setup_experiment_ = nullptr;
  fmi2EnterInitializationModeTYPE* enter_init_ = nullptr;
  fmi2ExitInitializationModeTYPE* exit_init_ = nullptr;
  fmi2TerminateTYPE* terminate_ = nullptr;
  fmi2GetRealTYPE* get_real_ = nullptr;
  fmi2SetRealTYPE* set_real_ = nullptr;
  fmi2GetIntegerTYPE* get_integer_ = nullptr;
  fmi2SetIntegerTYPE* set_integer_ = nullptr;
  fmi2GetBooleanTYPE* get_boolean_ = nullptr;
  fmi2SetBooleanTYPE* set_boolean_ = nullptr;
  fmi2DoStepTYPE* do_step_ = nullptr;
  fmi2EnterEventModeTYPE* enter_event_mode_ = nullptr;
  fmi2NewDiscreteStatesTYPE* new_discrete_states_ = nullptr;
  fmi2EnterContinuousTimeModeTYPE* enter_ct_mode_ = nullptr;
  fmi2CompletedIntegratorStepTYPE* completed_step_ = nullptr;
  fmi2SetTimeTYPE* set_time_ = nullptr;
  fmi2SetContinuousStatesTYPE* set_states_ = nullptr;
  fmi2GetContinuousStatesTYPE* get_states_ = nullptr;
  fmi2GetDerivativesTYPE* get_derivatives_ = nullptr;
  fmi2GetEventIndicatorsTYPE* get_indicators_ = nullptr;
  fmi2GetFMUstateTYPE* get_state_ = nullptr;
  fmi2SetFMUstateTYPE* set_state_ = nullptr;
  fmi2FreeFMUstateTYPE* free_state_ = nullptr;
  fmi2SerializedFMUstateSizeTYPE* state_size_ = nullptr;
  fmi2SerializeFMUstateTYPE* serialize_ = nullptr;
  fmi2DeSerializeFMUstateTYPE* deserialize_ = nullptr;
};

}  // namespace

std::unique_ptr<FmuInstance> make_fmi2_instance(const FmuArchive& archive, InterfaceKind kind,
                                                const std::string& instance_name) {
  return std::make_unique<Fmi2Instance>(archive, kind, instance_name);
}

}  // namespace mechsim::fmi
