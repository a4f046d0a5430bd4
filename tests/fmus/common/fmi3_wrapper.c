/* FMI 3.0 entry points of the test FMUs, co-simulation and model exchange in one binary,
 * over the model of model.h, compiled against mechsim/fmi/fmi3_functions.h.
 * Build-time faults: FMU_OMIT_DO_STEP (no fmi3DoStep), FMU_INSTANTIATE_FAILS (both
 * instantiate functions return NULL), FMU_INSTANTIATE_ABORTS (they abort the process). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mechsim/fmi/fmi3_functions.h"
#include "model.h"

#define EXPORT __attribute__((visibility("default")))

typedef struct {
  Model model;
  fmi3InstanceEnvironment environment;
  fmi3LogMessageCallback log;
} Instance;

static fmi3Status fail(Instance* s, const char* message) {
  if (s->log) s->log(s->environment, fmi3Error, "error", message);
  return fmi3Error;
}

static int valid(fmi3ValueReference vr) { return vr < (fmi3ValueReference)model_number_of_variables; }

static Instance* instantiate(fmi3InstanceEnvironment environment, fmi3LogMessageCallback log) {
#ifdef FMU_INSTANTIATE_ABORTS
  abort();
#endif
#ifdef FMU_INSTANTIATE_FAILS
  if (log) log(environment, fmi3Error, "error", "this FMU never instantiates");
  return NULL;
#else
  Instance* s = calloc(1, sizeof(Instance));
  if (!s) return NULL;
  s->environment = environment;
  s->log = log;
  model_defaults(&s->model);
  return s;
#endif
}

EXPORT fmi3GetVersionTYPE fmi3GetVersion;
const char* fmi3GetVersion(void) { return "3.0"; }

EXPORT fmi3InstantiateModelExchangeTYPE fmi3InstantiateModelExchange;
fmi3Instance fmi3InstantiateModelExchange(fmi3String name, fmi3String token, fmi3String resources,
                                          fmi3Boolean visible, fmi3Boolean logging,
                                          fmi3InstanceEnvironment environment, fmi3LogMessageCallback log) {
  return instantiate(environment, log);
}
EXPORT fmi3InstantiateCoSimulationTYPE fmi3InstantiateCoSimulation;
fmi3Instance fmi3InstantiateCoSimulation(fmi3String name, fmi3String token, fmi3String resources,
                                         fmi3Boolean visible, fmi3Boolean logging, fmi3Boolean event_mode_used,
                                         fmi3Boolean early_return_allowed, const fmi3ValueReference required[],
                                         size_t n_required, fmi3InstanceEnvironment environment,
                                         fmi3LogMessageCallback log, fmi3IntermediateUpdateCallback update) {
  return instantiate(environment, log);
}
EXPORT fmi3FreeInstanceTYPE fmi3FreeInstance;
void fmi3FreeInstance(fmi3Instance instance) { free(instance); }

EXPORT fmi3EnterInitializationModeTYPE fmi3EnterInitializationMode;
fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean tol_defined, fmi3Float64 tol,
                                       fmi3Float64 start, fmi3Boolean stop_defined, fmi3Float64 stop) {
  ((Instance*)instance)->model.time = start;
  return fmi3OK;
}
EXPORT fmi3ExitInitializationModeTYPE fmi3ExitInitializationMode;
fmi3Status fmi3ExitInitializationMode(fmi3Instance instance) {
  Instance* s = instance;
  model_initialize(&s->model);
  model_outputs(&s->model);
  return fmi3OK;
}
EXPORT fmi3TerminateTYPE fmi3Terminate;
fmi3Status fmi3Terminate(fmi3Instance instance) { return fmi3OK; }

EXPORT fmi3GetFloat64TYPE fmi3GetFloat64;
fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Float64 v[],
                          size_t nv) {
  Instance* s = instance;
  if (n != nv) return fail(s, "one value per value reference expected");
  model_outputs(&s->model);
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    v[i] = s->model.value[vr[i]];
  }
  return fmi3OK;
}
EXPORT fmi3GetInt32TYPE fmi3GetInt32;
fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Int32 v[], size_t nv) {
  Instance* s = instance;
  if (n != nv) return fail(s, "one value per value reference expected");
  model_outputs(&s->model);
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    v[i] = (fmi3Int32)s->model.value[vr[i]];
  }
  return fmi3OK;
}
EXPORT fmi3GetBooleanTYPE fmi3GetBoolean;
fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, fmi3Boolean v[],
                          size_t nv) {
  Instance* s = instance;
  if (n != nv) return fail(s, "one value per value reference expected");
  model_outputs(&s->model);
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    v[i] = s->model.value[vr[i]] != 0.0;
  }
  return fmi3OK;
}
EXPORT fmi3SetFloat64TYPE fmi3SetFloat64;
fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Float64 v[],
                          size_t nv) {
  Instance* s = instance;
  if (n != nv) return fail(s, "one value per value reference expected");
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    s->model.value[vr[i]] = v[i];
  }
  return fmi3OK;
}
EXPORT fmi3SetInt32TYPE fmi3SetInt32;
fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Int32 v[],
                        size_t nv) {
  Instance* s = instance;
  if (n != nv) return fail(s, "one value per value reference expected");
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    s->model.value[vr[i]] = v[i];
  }
  return fmi3OK;
}
EXPORT fmi3SetBooleanTYPE fmi3SetBoolean;
fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, const fmi3Boolean v[],
                          size_t nv) {
  Instance* s = instance;
  if (n != nv) return fail(s, "one value per value reference expected");
  for (size_t i = 0; i < n; ++i) {
    if (!valid(vr[i])) return fail(s, "unknown value reference");
    s->model.value[vr[i]] = v[i] ? 1.0 : 0.0;
  }
  return fmi3OK;
}

/* --- FMU state: a copy of the model (serialize = memcpy); the description's flags decide
 * whether an importer may use these. --- */
EXPORT fmi3GetFMUStateTYPE fmi3GetFMUState;
fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState* state) {
  Instance* s = instance;
  Model* copy = *state ? (Model*)*state : malloc(sizeof(Model));
  if (!copy) return fail(s, "out of memory");
  *copy = s->model;
  copy->error = NULL;
  *state = copy;
  return fmi3OK;
}
EXPORT fmi3SetFMUStateTYPE fmi3SetFMUState;
fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState state) {
  Instance* s = instance;
  if (!state) return fail(s, "fmi3SetFMUState: no state");
  s->model = *(const Model*)state;
  return fmi3OK;
}
EXPORT fmi3FreeFMUStateTYPE fmi3FreeFMUState;
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState* state) {
  free(*state);
  *state = NULL;
  return fmi3OK;
}
EXPORT fmi3SerializedFMUStateSizeTYPE fmi3SerializedFMUStateSize;
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState state, size_t* size) {
  *size = sizeof(Model);
  return fmi3OK;
}
EXPORT fmi3SerializeFMUStateTYPE fmi3SerializeFMUState;
fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState state, fmi3Byte bytes[], size_t size) {
  if (size != sizeof(Model)) return fail(instance, "fmi3SerializeFMUState: wrong size");
  memcpy(bytes, state, sizeof(Model));
  return fmi3OK;
}
EXPORT fmi3DeserializeFMUStateTYPE fmi3DeserializeFMUState;
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte bytes[], size_t size,
                                   fmi3FMUState* state) {
  if (size != sizeof(Model)) return fail(instance, "fmi3DeserializeFMUState: the bytes are not a state of this model");
  Model* copy = malloc(sizeof(Model));
  if (!copy) return fail(instance, "out of memory");
  memcpy(copy, bytes, sizeof(Model));
  copy->error = NULL;
  *state = copy;
  return fmi3OK;
}

/* --- co-simulation --- */
#ifndef FMU_OMIT_DO_STEP
EXPORT fmi3DoStepTYPE fmi3DoStep;
fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 t, fmi3Float64 h, fmi3Boolean no_prior,
                      fmi3Boolean* event_needed, fmi3Boolean* terminate, fmi3Boolean* early_return,
                      fmi3Float64* last_time) {
  Instance* s = instance;
  *event_needed = false;
  *terminate = false;
  *early_return = false;
  *last_time = t;
  if (model_check(&s->model, t + h)) return fail(s, s->model.error);
  model_advance(&s->model, t + h);
  *last_time = t + h;
  return fmi3OK;
}
#endif

/* --- model exchange --- */
EXPORT fmi3EnterEventModeTYPE fmi3EnterEventMode;
fmi3Status fmi3EnterEventMode(fmi3Instance instance) { return fmi3OK; }
EXPORT fmi3UpdateDiscreteStatesTYPE fmi3UpdateDiscreteStates;
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean* need_update, fmi3Boolean* terminate,
                                    fmi3Boolean* nominals_changed, fmi3Boolean* values_changed,
                                    fmi3Boolean* next_defined, fmi3Float64* next_time) {
  Instance* s = instance;
  *need_update = false;
  *terminate = false;
  *nominals_changed = false;
  *values_changed = model_event(&s->model) != 0;
  const double next = next_time_event(&s->model);
  *next_defined = isfinite(next);
  *next_time = isfinite(next) ? next : 0.0;
  return fmi3OK;
}
EXPORT fmi3EnterContinuousTimeModeTYPE fmi3EnterContinuousTimeMode;
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance) { return fmi3OK; }
EXPORT fmi3CompletedIntegratorStepTYPE fmi3CompletedIntegratorStep;
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance, fmi3Boolean no_prior, fmi3Boolean* enter_event,
                                       fmi3Boolean* terminate) {
  *enter_event = false;
  *terminate = false;
  return fmi3OK;
}
EXPORT fmi3SetTimeTYPE fmi3SetTime;
fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 t) {
  ((Instance*)instance)->model.time = t;
  return fmi3OK;
}
EXPORT fmi3SetContinuousStatesTYPE fmi3SetContinuousStates;
fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 x[], size_t nx) {
  Instance* s = instance;
  if (nx != (size_t)model_number_of_states) return fail(s, "wrong number of continuous states");
  memcpy(s->model.x, x, nx * sizeof(double));
  return fmi3OK;
}
EXPORT fmi3GetContinuousStatesTYPE fmi3GetContinuousStates;
fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 x[], size_t nx) {
  Instance* s = instance;
  if (nx != (size_t)model_number_of_states) return fail(s, "wrong number of continuous states");
  memcpy(x, s->model.x, nx * sizeof(double));
  return fmi3OK;
}
EXPORT fmi3GetContinuousStateDerivativesTYPE fmi3GetContinuousStateDerivatives;
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 dxdt[], size_t nx) {
  Instance* s = instance;
  if (nx != (size_t)model_number_of_states) return fail(s, "wrong number of continuous states");
  if (model_check(&s->model, s->model.time)) return fail(s, s->model.error);
  model_derivatives(&s->model, dxdt);
  return fmi3OK;
}
EXPORT fmi3GetEventIndicatorsTYPE fmi3GetEventIndicators;
fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 z[], size_t nz) {
  Instance* s = instance;
  if (nz != (size_t)model_number_of_indicators) return fail(s, "wrong number of event indicators");
  model_event_indicators(&s->model, z);
  return fmi3OK;
}
