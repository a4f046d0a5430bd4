// FMI 2.0 co-simulation entry points of an exported mechsim participant (FMI 2.0.5 §2.1,
// §4.2), over ExportedParticipant. Declared with the importer's own function types
// (mechsim/fmi/fmi2_functions.h), so a signature that differs from what mechsim loads is a
// compile error. Every function the standard requires is present; those of capabilities
// the modelDescription does not claim (directional and input/output derivatives,
// asynchronous steps, strings) log why and return fmi2Error.
#include <cstdarg>
#include <cstring>
#include <limits>
#include <string>

#include "participant_resources.h"
#include "mechsim/fmi/fmi2_functions.h"

#define MECHSIM_FMI_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

using mechsim::fmi_export::ExportedParticipant;

struct Instance {
  std::string name;
  fmi2CallbackFunctions callbacks{};
  bool logging = false;
  std::unique_ptr<ExportedParticipant> core;
  double start = 0.0, stop = 0.0;
  bool stop_defined = false;
};

fmi2Status log_error(const Instance* s, fmi2Status status, const std::string& message) {
  if (s != nullptr && s->callbacks.logger != nullptr)
    s->callbacks.logger(s->callbacks.componentEnvironment, s->name.c_str(), status, "error", "%s", message.c_str());
  return status;
}

// Runs `body` and turns an exception into fmi2Error with the message logged.
template <class F>
fmi2Status guarded(fmi2Component c, const char* function, F&& body) {
  auto* s = static_cast<Instance*>(c);
  if (s == nullptr) return fmi2Error;
  try {
    body(*s);
    return fmi2OK;
  } catch (const std::exception& e) {
    return log_error(s, fmi2Error, std::string(function) + ": " + e.what());
  }
}

fmi2Status unsupported(fmi2Component c, const char* function, const char* why) {
  return log_error(static_cast<Instance*>(c), fmi2Error, std::string(function) + " is not supported: " + why);
}

}  // namespace

MECHSIM_FMI_EXPORT fmi2GetTypesPlatformTYPE fmi2GetTypesPlatform;
const char* fmi2GetTypesPlatform(void) { return "default"; }
MECHSIM_FMI_EXPORT fmi2GetVersionTYPE fmi2GetVersion;
const char* fmi2GetVersion(void) { return "2.0"; }

MECHSIM_FMI_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t, const fmi2String[]) {
  if (c == nullptr) return fmi2Error;
  static_cast<Instance*>(c)->logging = on != fmi2False;
  return fmi2OK;
}

MECHSIM_FMI_EXPORT fmi2InstantiateTYPE fmi2Instantiate;
fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String, fmi2String resources,
                              const fmi2CallbackFunctions* functions, fmi2Boolean, fmi2Boolean logging) {
  auto s = std::make_unique<Instance>();
  s->name = name != nullptr ? name : "";
  if (functions != nullptr) s->callbacks = *functions;
  s->logging = logging != fmi2False;
  if (type != fmi2CoSimulation) {
    log_error(s.get(), fmi2Error, "fmi2Instantiate: this FMU offers co-simulation only (an exported mechsim participant)");
    return nullptr;
  }
  try {
    if (resources == nullptr) throw std::runtime_error("no resource location given");
    s->core = mechsim::fmi_export::load_participant(resources);
  } catch (const std::exception& e) {
    log_error(s.get(), fmi2Error, std::string("fmi2Instantiate: ") + e.what());
    return nullptr;
  }
  return s.release();
}

MECHSIM_FMI_EXPORT fmi2FreeInstanceTYPE fmi2FreeInstance;
void fmi2FreeInstance(fmi2Component c) { delete static_cast<Instance*>(c); }

MECHSIM_FMI_EXPORT fmi2SetupExperimentTYPE fmi2SetupExperiment;
fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real start, fmi2Boolean stop_defined,
                               fmi2Real stop) {
  // The tolerance is not taken: the participant's solver runs at the scene's tolerances.
  return guarded(c, "fmi2SetupExperiment", [&](Instance& s) {
    s.start = start;
    s.stop_defined = stop_defined != fmi2False;
    s.stop = stop;
  });
}

MECHSIM_FMI_EXPORT fmi2EnterInitializationModeTYPE fmi2EnterInitializationMode;
fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode", [](Instance& s) {
    s.core->enter_initialization(s.start, s.stop_defined ? s.stop : std::numeric_limits<double>::infinity());
  });
}
MECHSIM_FMI_EXPORT fmi2ExitInitializationModeTYPE fmi2ExitInitializationMode;
fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode", [](Instance& s) { s.core->exit_initialization(); });
}
MECHSIM_FMI_EXPORT fmi2TerminateTYPE fmi2Terminate;
fmi2Status fmi2Terminate(fmi2Component c) { return guarded(c, "fmi2Terminate", [](Instance&) {}); }
MECHSIM_FMI_EXPORT fmi2Status fmi2Reset(fmi2Component c) {
  return unsupported(c, "fmi2Reset", "instantiate the FMU again");
}

MECHSIM_FMI_EXPORT fmi2GetRealTYPE fmi2GetReal;
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
  return guarded(c, "fmi2GetReal", [&](Instance& s) {
    for (size_t i = 0; i < n; ++i) value[i] = s.core->get_real(vr[i]);
  });
}
MECHSIM_FMI_EXPORT fmi2SetRealTYPE fmi2SetReal;
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
  return guarded(c, "fmi2SetReal", [&](Instance& s) {
    for (size_t i = 0; i < n; ++i) s.core->set_real(vr[i], value[i]);
  });
}
// The exported variables are all Real: any other type's value reference is unknown.
MECHSIM_FMI_EXPORT fmi2GetIntegerTYPE fmi2GetInteger;
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t n, fmi2Integer[]) {
  return n == 0 ? fmi2OK : unsupported(c, "fmi2GetInteger", "the FMU has no Integer variables");
}
MECHSIM_FMI_EXPORT fmi2SetIntegerTYPE fmi2SetInteger;
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t n, const fmi2Integer[]) {
  return n == 0 ? fmi2OK : unsupported(c, "fmi2SetInteger", "the FMU has no Integer variables");
}
MECHSIM_FMI_EXPORT fmi2GetBooleanTYPE fmi2GetBoolean;
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t n, fmi2Boolean[]) {
  return n == 0 ? fmi2OK : unsupported(c, "fmi2GetBoolean", "the FMU has no Boolean variables");
}
MECHSIM_FMI_EXPORT fmi2SetBooleanTYPE fmi2SetBoolean;
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t n, const fmi2Boolean[]) {
  return n == 0 ? fmi2OK : unsupported(c, "fmi2SetBoolean", "the FMU has no Boolean variables");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t n, fmi2String[]) {
  return n == 0 ? fmi2OK : unsupported(c, "fmi2GetString", "the FMU has no String variables");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t n, const fmi2String[]) {
  return n == 0 ? fmi2OK : unsupported(c, "fmi2SetString", "the FMU has no String variables");
}

// FMU state: a copy of ExportedParticipant::State (restoring it continues bit for bit).
using State = ExportedParticipant::State;
MECHSIM_FMI_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return guarded(c, "fmi2GetFMUstate", [&](Instance& s) {
    if (*state != nullptr) *static_cast<State*>(*state) = s.core->state();  // the importer reuses it
    else *state = new State(s.core->state());
  });
}
MECHSIM_FMI_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  return guarded(c, "fmi2SetFMUstate", [&](Instance& s) {
    if (state == nullptr) throw std::invalid_argument("no FMU state given");
    s.core->set_state(*static_cast<const State*>(state));
  });
}
MECHSIM_FMI_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return guarded(c, "fmi2FreeFMUstate", [&](Instance&) {
    delete static_cast<State*>(*state);
    *state = nullptr;
  });
}
MECHSIM_FMI_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  return guarded(c, "fmi2SerializedFMUstateSize", [&](Instance&) {
    *size = ExportedParticipant::serialize(*static_cast<const State*>(state)).size();
  });
}
MECHSIM_FMI_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, char bytes[], size_t size) {
  return guarded(c, "fmi2SerializeFMUstate", [&](Instance&) {
    const auto serialized = ExportedParticipant::serialize(*static_cast<const State*>(state));
    if (size < serialized.size()) throw std::invalid_argument("the buffer is smaller than fmi2SerializedFMUstateSize");
    std::memcpy(bytes, serialized.data(), serialized.size());
  });
}
MECHSIM_FMI_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const char bytes[], size_t size,
                                                      fmi2FMUstate* state) {
  return guarded(c, "fmi2DeSerializeFMUstate", [&](Instance&) {
    State read = ExportedParticipant::deserialize(reinterpret_cast<const unsigned char*>(bytes), size);
    if (*state != nullptr) *static_cast<State*>(*state) = std::move(read);
    else *state = new State(std::move(read));
  });
}

// Capabilities not claimed (providesDirectionalDerivative, canInterpolateInputs,
// maxOutputDerivativeOrder = 0, canRunAsynchronuously are false in the modelDescription).
MECHSIM_FMI_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                                           const fmi2ValueReference[], size_t, const fmi2Real[],
                                                           fmi2Real[]) {
  return unsupported(c, "fmi2GetDirectionalDerivative", "providesDirectionalDerivative is false");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                                          const fmi2Integer[], const fmi2Real[]) {
  return unsupported(c, "fmi2SetRealInputDerivatives", "canInterpolateInputs is false (inputs are held over a step)");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                                           const fmi2Integer[], fmi2Real[]) {
  return unsupported(c, "fmi2GetRealOutputDerivatives", "maxOutputDerivativeOrder is 0");
}

MECHSIM_FMI_EXPORT fmi2DoStepTYPE fmi2DoStep;
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean) {
  return guarded(c, "fmi2DoStep", [&](Instance& s) { s.core->do_step(t, h); });
}
MECHSIM_FMI_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) {
  return unsupported(c, "fmi2CancelStep", "steps are synchronous (canRunAsynchronuously is false)");
}
// fmi2StatusKind: fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated.
MECHSIM_FMI_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, int, fmi2Status*) {
  return unsupported(c, "fmi2GetStatus", "steps are synchronous");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, int kind, fmi2Real* value) {
  if (kind == 2 && c != nullptr && value != nullptr) {  // fmi2LastSuccessfulTime
    *value = static_cast<Instance*>(c)->core->time();
    return fmi2OK;
  }
  return unsupported(c, "fmi2GetRealStatus", "only fmi2LastSuccessfulTime is answered");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, int, fmi2Integer*) {
  return unsupported(c, "fmi2GetIntegerStatus", "steps are synchronous");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, int, fmi2Boolean*) {
  return unsupported(c, "fmi2GetBooleanStatus", "steps are synchronous");
}
MECHSIM_FMI_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, int, fmi2String*) {
  return unsupported(c, "fmi2GetStringStatus", "steps are synchronous");
}
