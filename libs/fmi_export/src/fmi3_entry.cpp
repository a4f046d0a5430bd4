// FMI 3.0 co-simulation entry points of an exported mechsim participant (FMI 3.0.2 §2.2,
// §4), over ExportedParticipant. Declared with the importer's own function types
// (mechsim/fmi/fmi3_functions.h) where it has them. The functions of capabilities the
// modelDescription does not claim (event mode, early return, derivatives) log why and
// return fmi3Error; those of interfaces and types it does not offer: fmi3_unsupported.cpp.
#include <cstring>
#include <limits>
#include <string>

#include "fmi3_export.h"
#include "participant_resources.h"

namespace {

using mechsim::fmi_export::ExportedParticipant;

struct Instance {
  std::string name;
  fmi3InstanceEnvironment environment = nullptr;
  fmi3LogMessageCallback log = nullptr;
  std::unique_ptr<ExportedParticipant> core;
};

fmi3Status log_error(const Instance* s, const std::string& message) {
  if (s != nullptr && s->log != nullptr) s->log(s->environment, fmi3Error, "error", message.c_str());
  return fmi3Error;
}

template <class F>
fmi3Status guarded(fmi3Instance c, const char* function, F&& body) {
  auto* s = static_cast<Instance*>(c);
  if (s == nullptr) return fmi3Error;
  try {
    body(*s);
    return fmi3OK;
  } catch (const std::exception& e) {
    return log_error(s, std::string(function) + ": " + e.what());
  }
}

fmi3Status unsupported(fmi3Instance c, const char* function, const char* why) {
  return log_error(static_cast<Instance*>(c), std::string(function) + " is not supported: " + why);
}

}  // namespace

fmi3Status mechsim::fmi_export::fmi3_unsupported(fmi3Instance instance, const char* function, const char* why) {
  return unsupported(instance, function, why);
}

MECHSIM_FMI_EXPORT fmi3GetVersionTYPE fmi3GetVersion;
const char* fmi3GetVersion(void) { return "3.0"; }

MECHSIM_FMI_EXPORT fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean, size_t, const fmi3String[]) {
  return c == nullptr ? fmi3Error : fmi3OK;
}

MECHSIM_FMI_EXPORT fmi3InstantiateCoSimulationTYPE fmi3InstantiateCoSimulation;
fmi3Instance fmi3InstantiateCoSimulation(fmi3String name, fmi3String, fmi3String resources, fmi3Boolean, fmi3Boolean,
                                         fmi3Boolean event_mode_used, fmi3Boolean early_return_allowed,
                                         const fmi3ValueReference[], size_t, fmi3InstanceEnvironment environment,
                                         fmi3LogMessageCallback log, fmi3IntermediateUpdateCallback) {
  auto s = std::make_unique<Instance>();
  s->name = name != nullptr ? name : "";
  s->environment = environment;
  s->log = log;
  if (event_mode_used) {
    log_error(s.get(), "fmi3InstantiateCoSimulation: event mode is not supported (hasEventMode is false)");
    return nullptr;
  }
  (void)early_return_allowed;  // never returns early (canReturnEarlyAfterIntermediateUpdate is false)
  try {
    if (resources == nullptr) throw std::runtime_error("no resource path given");
    s->core = mechsim::fmi_export::load_participant(resources);
  } catch (const std::exception& e) {
    log_error(s.get(), std::string("fmi3InstantiateCoSimulation: ") + e.what());
    return nullptr;
  }
  return s.release();
}

MECHSIM_FMI_EXPORT fmi3InstantiateModelExchangeTYPE fmi3InstantiateModelExchange;
fmi3Instance fmi3InstantiateModelExchange(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                          fmi3InstanceEnvironment environment, fmi3LogMessageCallback log) {
  if (log != nullptr)
    log(environment, fmi3Error, "error", "this FMU offers co-simulation only (an exported mechsim participant)");
  return nullptr;
}
MECHSIM_FMI_EXPORT fmi3Instance fmi3InstantiateScheduledExecution(fmi3String, fmi3String, fmi3String, fmi3Boolean,
                                                                  fmi3Boolean, fmi3InstanceEnvironment environment,
                                                                  fmi3LogMessageCallback log, void*, void*, void*) {
  if (log != nullptr)
    log(environment, fmi3Error, "error", "this FMU offers co-simulation only (an exported mechsim participant)");
  return nullptr;
}

MECHSIM_FMI_EXPORT fmi3FreeInstanceTYPE fmi3FreeInstance;
void fmi3FreeInstance(fmi3Instance c) { delete static_cast<Instance*>(c); }

MECHSIM_FMI_EXPORT fmi3EnterInitializationModeTYPE fmi3EnterInitializationMode;
fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean, fmi3Float64, fmi3Float64 start,
                                       fmi3Boolean stop_defined, fmi3Float64 stop) {
  // The tolerance is not taken: the participant's solver runs at the scene's tolerances.
  return guarded(c, "fmi3EnterInitializationMode", [&](Instance& s) {
    s.core->enter_initialization(start, stop_defined ? stop : std::numeric_limits<double>::infinity());
  });
}
MECHSIM_FMI_EXPORT fmi3ExitInitializationModeTYPE fmi3ExitInitializationMode;
fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
  return guarded(c, "fmi3ExitInitializationMode", [](Instance& s) { s.core->exit_initialization(); });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3EnterEventMode(fmi3Instance c) {
  return unsupported(c, "fmi3EnterEventMode", "hasEventMode is false");
}
MECHSIM_FMI_EXPORT fmi3TerminateTYPE fmi3Terminate;
fmi3Status fmi3Terminate(fmi3Instance c) { return guarded(c, "fmi3Terminate", [](Instance&) {}); }
MECHSIM_FMI_EXPORT fmi3Status fmi3Reset(fmi3Instance c) { return unsupported(c, "fmi3Reset", "instantiate the FMU again"); }

MECHSIM_FMI_EXPORT fmi3GetFloat64TYPE fmi3GetFloat64;
fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n, fmi3Float64 value[], size_t nv) {
  return guarded(c, "fmi3GetFloat64", [&](Instance& s) {
    if (nv != n) throw std::invalid_argument("expected one value per value reference (all variables are scalars)");
    for (size_t i = 0; i < n; ++i) value[i] = s.core->get_real(vr[i]);
  });
}
MECHSIM_FMI_EXPORT fmi3SetFloat64TYPE fmi3SetFloat64;
fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n, const fmi3Float64 value[], size_t nv) {
  return guarded(c, "fmi3SetFloat64", [&](Instance& s) {
    if (nv != n) throw std::invalid_argument("expected one value per value reference (all variables are scalars)");
    for (size_t i = 0; i < n; ++i) s.core->set_real(vr[i], value[i]);
  });
}
MECHSIM_FMI_EXPORT fmi3GetInt32TYPE fmi3GetInt32;
fmi3Status fmi3GetInt32(fmi3Instance c, const fmi3ValueReference[], size_t n, fmi3Int32[], size_t) {
  return n == 0 ? fmi3OK : unsupported(c, "fmi3GetInt32", "the FMU has no Int32 variables");
}
MECHSIM_FMI_EXPORT fmi3SetInt32TYPE fmi3SetInt32;
fmi3Status fmi3SetInt32(fmi3Instance c, const fmi3ValueReference[], size_t n, const fmi3Int32[], size_t) {
  return n == 0 ? fmi3OK : unsupported(c, "fmi3SetInt32", "the FMU has no Int32 variables");
}
MECHSIM_FMI_EXPORT fmi3GetBooleanTYPE fmi3GetBoolean;
fmi3Status fmi3GetBoolean(fmi3Instance c, const fmi3ValueReference[], size_t n, fmi3Boolean[], size_t) {
  return n == 0 ? fmi3OK : unsupported(c, "fmi3GetBoolean", "the FMU has no Boolean variables");
}
MECHSIM_FMI_EXPORT fmi3SetBooleanTYPE fmi3SetBoolean;
fmi3Status fmi3SetBoolean(fmi3Instance c, const fmi3ValueReference[], size_t n, const fmi3Boolean[], size_t) {
  return n == 0 ? fmi3OK : unsupported(c, "fmi3SetBoolean", "the FMU has no Boolean variables");
}

// FMU state: a copy of ExportedParticipant::State (restoring it continues bit for bit).
using State = ExportedParticipant::State;
MECHSIM_FMI_EXPORT fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState* state) {
  return guarded(c, "fmi3GetFMUState", [&](Instance& s) {
    if (*state != nullptr) *static_cast<State*>(*state) = s.core->state();
    else *state = new State(s.core->state());
  });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState state) {
  return guarded(c, "fmi3SetFMUState", [&](Instance& s) {
    if (state == nullptr) throw std::invalid_argument("no FMU state given");
    s.core->set_state(*static_cast<const State*>(state));
  });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState* state) {
  return guarded(c, "fmi3FreeFMUState", [&](Instance&) {
    delete static_cast<State*>(*state);
    *state = nullptr;
  });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState state, size_t* size) {
  return guarded(c, "fmi3SerializedFMUStateSize", [&](Instance&) {
    *size = ExportedParticipant::serialize(*static_cast<const State*>(state)).size();
  });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState state, uint8_t bytes[], size_t size) {
  return guarded(c, "fmi3SerializeFMUState", [&](Instance&) {
    const auto serialized = ExportedParticipant::serialize(*static_cast<const State*>(state));
    if (size < serialized.size()) throw std::invalid_argument("the buffer is smaller than fmi3SerializedFMUStateSize");
    std::memcpy(bytes, serialized.data(), serialized.size());
  });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const uint8_t bytes[], size_t size,
                                                      fmi3FMUState* state) {
  return guarded(c, "fmi3DeserializeFMUState", [&](Instance&) {
    State read = ExportedParticipant::deserialize(bytes, size);
    if (*state != nullptr) *static_cast<State*>(*state) = std::move(read);
    else *state = new State(std::move(read));
  });
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetDirectionalDerivative(fmi3Instance c, const fmi3ValueReference[], size_t,
                                                           const fmi3ValueReference[], size_t, const fmi3Float64[],
                                                           size_t, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetDirectionalDerivative", "providesDirectionalDerivatives is false");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetAdjointDerivative(fmi3Instance c, const fmi3ValueReference[], size_t,
                                                       const fmi3ValueReference[], size_t, const fmi3Float64[], size_t,
                                                       fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetAdjointDerivative", "providesAdjointDerivatives is false");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference[], size_t,
                                                       const fmi3Int32[], fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder is 0");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3EnterStepMode(fmi3Instance c) {
  // Initialization mode ends in step mode already (no event mode).
  return c == nullptr ? fmi3Error : fmi3OK;
}

MECHSIM_FMI_EXPORT fmi3DoStepTYPE fmi3DoStep;
fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean, fmi3Boolean* event_handling_needed,
                      fmi3Boolean* terminate_simulation, fmi3Boolean* early_return, fmi3Float64* last_successful_time) {
  return guarded(c, "fmi3DoStep", [&](Instance& s) {
    s.core->do_step(t, h);
    if (event_handling_needed) *event_handling_needed = false;
    if (terminate_simulation) *terminate_simulation = false;
    if (early_return) *early_return = false;
    if (last_successful_time) *last_successful_time = s.core->time();
  });
}
