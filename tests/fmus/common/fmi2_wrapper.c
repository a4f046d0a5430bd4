/* FMI 2.0 entry points of the test FMUs, co-simulation and model exchange in one binary,
 * over the model of model.h. Compiled against the importer's own declarations
 * (mechsim/fmi/fmi2_functions.h), so the exported signatures are checked by the compiler.
 *
 * Build-time faults for the importer's error tests:
 *   FMU_OMIT_DO_STEP         the binary lacks fmi2DoStep
 *   FMU_INSTANTIATE_FAILS    fmi2Instantiate returns NULL
 *   FMU_INSTANTIATE_ABORTS   fmi2Instantiate aborts the process (an importer must survive it) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mechsim/fmi/fmi2_functions.h"
#include "model.h"

#define EXPORT __attribute__((visibility("default")))

typedef struct {
  Model model;
  fmi2CallbackFunctions callbacks;
  char name[64];
  fmi2Type type;
} Instance;

static fmi2Status fail(Instance* s, const char* message) {
  if (s->callbacks.logger)
    s->callbacks.logger(s->callbacks.componentEnvironment, s->name, fmi2Error, "error", "%s", message);
  return fmi2Error;
}

static int valid(fmi2ValueReference vr) { return vr < (fmi2ValueReference)model_number_of_variables; }

EXPORT fmi2GetTypesPlatformTYPE fmi2GetTypesPlatform;
const char* fmi2GetTypesPlatform(void) { return "default"; }
EXPORT fmi2GetVersionTYPE fmi2GetVersion;
const char* fmi2GetVersion(void) { return "2.0"; }

EXPORT fmi2InstantiateTYPE fmi2Instantiate;
fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String resources,
                              const fmi2CallbackFunctions* functions, fmi2Boolean visible, fmi2Boolean logging) {
#ifdef FMU_INSTANTIATE_ABORTS
  abort();
#endif
#ifdef FMU_INSTANTIATE_FAILS
  if (functions && functions->logger)
    functions->logger(functions->componentEnvironment, name, fmi2Error, "error", "this FMU never instantiates");
  return NULL;
#else
  Instance* s = calloc(1, sizeof(Instance));
  if (!s) return NULL;
  s->callbacks = *functions;
  strncpy(s->name, name ? name : "", sizeof s->name - 1);
  s->type = type;
  model_defaults(&s->model);
  return s;
#endif
}

EXPORT fmi2FreeInstanceTYPE fmi2FreeInstance;
void fmi2FreeInstance(fmi2Component c) { free(c); }

EXPORT fmi2SetupExperimentTYPE fmi2SetupExperiment;
fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tol_defined, fmi2Real tol, fmi2Real start,
                               fmi2Boolean stop_defined, fmi2Real stop) {
  ((Instance*)c)->model.time = start;
  return fmi2OK;
}
EXPORT fmi2EnterInitializationModeTYPE fmi2EnterInitializationMode;
fmi2Status fmi2EnterInitializationMode(fmi2Component c) { return fmi2OK; }
EXPORT fmi2ExitInitializationModeTYPE fmi2ExitInitializationMode;
fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  Instance* s = c;
  model_initialize(&s->model);
  model_outputs(&s->model);
  return fmi2OK;
}
EXPORT fmi2TerminateTYPE fmi2Terminate;
fmi2Status fmi2Terminate(fmi2Component c) { return fmi2OK; }

EXPORT fmi2GetRealTYPE fmi2GetReal;
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
  Instance* s = c;
  model_outputs(&s->model);
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    value[i] = s->model.value[vr[i]];
  }
  return fmi2OK;
}
EXPORT fmi2GetIntegerTYPE fmi2GetInteger;
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer value[]) {
  Instance* s = c;
  model_outputs(&s->model);
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    value[i] = (fmi2Integer)s->model.value[vr[i]];
  }
  return fmi2OK;
}
EXPORT fmi2GetBooleanTYPE fmi2GetBoolean;
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean value[]) {
  Instance* s = c;
  model_outputs(&s->model);
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    value[i] = s->model.value[vr[i]] != 0.0;
  }
  return fmi2OK;
}
EXPORT fmi2SetRealTYPE fmi2SetReal;
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
  Instance* s = c;
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    s->model.value[vr[i]] = value[i];
  }
  return fmi2OK;
}
EXPORT fmi2SetIntegerTYPE fmi2SetInteger;
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer value[]) {
  Instance* s = c;
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    s->model.value[vr[i]] = value[i];
  }
  return fmi2OK;
}
EXPORT fmi2SetBooleanTYPE fmi2SetBoolean;
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean value[]) {
  Instance* s = c;
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    s->model.value[vr[i]] = value[i] ? 1.0 : 0.0;
  }
  return fmi2OK;
}

/* --- FMU state: a copy of the model (the state is the Model struct; serialize = memcpy).
 * Exported always; the description's flags decide whether an importer may use them. --- */
EXPORT fmi2GetFMUstateTYPE fmi2GetFMUstate;
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  Instance* s = c;
  Model* copy = *state ? (Model*)*state : malloc(sizeof(Model));
  if (!copy) return fail(s, "out of memory");
  *copy = s->model;
  copy->error = NULL;
  *state = copy;
  return fmi2OK;
}
EXPORT fmi2SetFMUstateTYPE fmi2SetFMUstate;
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  Instance* s = c;
  if (!state) return fail(s, "fmi2SetFMUstate: no state");
  s->model = *(const Model*)state;
  return fmi2OK;
}
EXPORT fmi2FreeFMUstateTYPE fmi2FreeFMUstate;
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  free(*state);
  *state = NULL;
  return fmi2OK;
}
EXPORT fmi2SerializedFMUstateSizeTYPE fmi2SerializedFMUstateSize;
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  *size = sizeof(Model);
  return fmi2OK;
}
EXPORT fmi2SerializeFMUstateTYPE fmi2SerializeFMUstate;
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
  if (size != sizeof(Model)) return fail(c, "fmi2SerializeFMUstate: wrong size");
  memcpy(bytes, state, sizeof(Model));
  return fmi2OK;
}
EXPORT fmi2DeSerializeFMUstateTYPE fmi2DeSerializeFMUstate;
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size, fmi2FMUstate* state) {
  if (size != sizeof(Model)) return fail(c, "fmi2DeSerializeFMUstate: the bytes are not a state of this model");
  Model* copy = malloc(sizeof(Model));
  if (!copy) return fail(c, "out of memory");
  memcpy(copy, bytes, sizeof(Model));
  copy->error = NULL;
  *state = copy;
  return fmi2OK;
}

/* --- co-simulation --- */
#ifndef FMU_OMIT_DO_STEP
EXPORT fmi2DoStepTYPE fmi2DoStep;
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean no_prior) {
  Instance* s = c;
  if (model_check(&s->model, t + h)) return fail(s, s->model.error);
  model_advance(&s->model, t + h);
  return fmi2OK;
}
#endif

/* --- model exchange --- */
EXPORT fmi2EnterEventModeTYPE fmi2EnterEventMode;
fmi2Status fmi2EnterEventMode(fmi2Component c) { return fmi2OK; }
EXPORT fmi2NewDiscreteStatesTYPE fmi2NewDiscreteStates;
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo* info) {
  Instance* s = c;
  info->newDiscreteStatesNeeded = fmi2False;
  info->terminateSimulation = fmi2False;
  info->nominalsOfContinuousStatesChanged = fmi2False;
  info->valuesOfContinuousStatesChanged = model_event(&s->model) ? fmi2True : fmi2False;
  const double next = next_time_event(&s->model);
  info->nextEventTimeDefined = isfinite(next) ? fmi2True : fmi2False;
  info->nextEventTime = isfinite(next) ? next : 0.0;
  return fmi2OK;
}
EXPORT fmi2EnterContinuousTimeModeTYPE fmi2EnterContinuousTimeMode;
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { return fmi2OK; }
EXPORT fmi2CompletedIntegratorStepTYPE fmi2CompletedIntegratorStep;
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean no_prior, fmi2Boolean* enter_event,
                                       fmi2Boolean* terminate) {
  *enter_event = fmi2False;
  *terminate = fmi2False;
  return fmi2OK;
}
EXPORT fmi2SetTimeTYPE fmi2SetTime;
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real t) {
  ((Instance*)c)->model.time = t;
  return fmi2OK;
}
EXPORT fmi2SetContinuousStatesTYPE fmi2SetContinuousStates;
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
  Instance* s = c;
  if (nx != (size_t)model_number_of_states) return fail(s, "wrong number of continuous states");
  memcpy(s->model.x, x, nx * sizeof(double));
  return fmi2OK;
}
EXPORT fmi2GetContinuousStatesTYPE fmi2GetContinuousStates;
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
  Instance* s = c;
  if (nx != (size_t)model_number_of_states) return fail(s, "wrong number of continuous states");
  memcpy(x, s->model.x, nx * sizeof(double));
  return fmi2OK;
}
EXPORT fmi2GetDerivativesTYPE fmi2GetDerivatives;
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dxdt[], size_t nx) {
  Instance* s = c;
  if (nx != (size_t)model_number_of_states) return fail(s, "wrong number of continuous states");
  if (model_check(&s->model, s->model.time)) return fail(s, s->model.error);
  model_derivatives(&s->model, dxdt);
  return fmi2OK;
}
EXPORT fmi2GetEventIndicatorsTYPE fmi2GetEventIndicators;
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t nz) {
  Instance* s = c;
  if (nz != (size_t)model_number_of_indicators) return fail(s, "wrong number of event indicators");
  model_event_indicators(&s->model, z);
  return fmi2OK;
}
