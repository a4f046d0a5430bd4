/* The FMI 3.0 C API as far as mechsim calls it (importer) or implements it (the test FMUs
 * of tests/fmus): the project's own declarations, written from the standard (FMI 3.0.2,
 * "2.2 FMI Application Programming Interface", "3 Model Exchange", "4 Co-Simulation").
 * Plain C, shared with the test FMUs so that a signature mismatch is a compile error there.
 * Only the *TYPE function types are declared; the importer resolves "fmi3<Function>". */
#ifndef MECHSIM_FMI_FMI3_FUNCTIONS_H
#define MECHSIM_FMI_FMI3_FUNCTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef void* fmi3Instance;
typedef void* fmi3InstanceEnvironment;
typedef void* fmi3FMUState;
typedef uint32_t fmi3ValueReference;
typedef double fmi3Float64;
typedef int32_t fmi3Int32;
typedef bool fmi3Boolean;
typedef char fmi3Char;
typedef uint8_t fmi3Byte;
typedef const fmi3Char* fmi3String;

typedef enum { fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal } fmi3Status;

typedef void (*fmi3LogMessageCallback)(fmi3InstanceEnvironment environment, fmi3Status status,
                                       fmi3String category, fmi3String message);
typedef void (*fmi3IntermediateUpdateCallback)(fmi3InstanceEnvironment environment, fmi3Float64 time,
                                               fmi3Boolean variable_set_requested,
                                               fmi3Boolean variable_get_allowed, fmi3Boolean step_finished,
                                               fmi3Boolean can_return_early, fmi3Boolean* early_return_requested,
                                               fmi3Float64* early_return_time);

/* Common functions */
typedef const char* fmi3GetVersionTYPE(void);
typedef fmi3Instance fmi3InstantiateModelExchangeTYPE(fmi3String instance_name, fmi3String instantiation_token,
                                                      fmi3String resource_path, fmi3Boolean visible,
                                                      fmi3Boolean logging_on, fmi3InstanceEnvironment environment,
                                                      fmi3LogMessageCallback log_message);
typedef fmi3Instance fmi3InstantiateCoSimulationTYPE(
    fmi3String instance_name, fmi3String instantiation_token, fmi3String resource_path, fmi3Boolean visible,
    fmi3Boolean logging_on, fmi3Boolean event_mode_used, fmi3Boolean early_return_allowed,
    const fmi3ValueReference required_intermediate_variables[], size_t n_required_intermediate_variables,
    fmi3InstanceEnvironment environment, fmi3LogMessageCallback log_message,
    fmi3IntermediateUpdateCallback intermediate_update);
typedef void fmi3FreeInstanceTYPE(fmi3Instance instance);
typedef fmi3Status fmi3EnterInitializationModeTYPE(fmi3Instance instance, fmi3Boolean tolerance_defined,
                                                   fmi3Float64 tolerance, fmi3Float64 start_time,
                                                   fmi3Boolean stop_time_defined, fmi3Float64 stop_time);
typedef fmi3Status fmi3ExitInitializationModeTYPE(fmi3Instance instance);
typedef fmi3Status fmi3TerminateTYPE(fmi3Instance instance);
typedef fmi3Status fmi3GetFloat64TYPE(fmi3Instance instance, const fmi3ValueReference vrs[], size_t n_vrs,
                                      fmi3Float64 values[], size_t n_values);
typedef fmi3Status fmi3GetInt32TYPE(fmi3Instance instance, const fmi3ValueReference vrs[], size_t n_vrs,
                                    fmi3Int32 values[], size_t n_values);
typedef fmi3Status fmi3GetBooleanTYPE(fmi3Instance instance, const fmi3ValueReference vrs[], size_t n_vrs,
                                      fmi3Boolean values[], size_t n_values);
typedef fmi3Status fmi3SetFloat64TYPE(fmi3Instance instance, const fmi3ValueReference vrs[], size_t n_vrs,
                                      const fmi3Float64 values[], size_t n_values);
typedef fmi3Status fmi3SetInt32TYPE(fmi3Instance instance, const fmi3ValueReference vrs[], size_t n_vrs,
                                    const fmi3Int32 values[], size_t n_values);
typedef fmi3Status fmi3SetBooleanTYPE(fmi3Instance instance, const fmi3ValueReference vrs[], size_t n_vrs,
                                      const fmi3Boolean values[], size_t n_values);
typedef fmi3Status fmi3EnterEventModeTYPE(fmi3Instance instance);
typedef fmi3Status fmi3UpdateDiscreteStatesTYPE(fmi3Instance instance, fmi3Boolean* discrete_states_need_update,
                                                fmi3Boolean* terminate_simulation,
                                                fmi3Boolean* nominals_changed, fmi3Boolean* values_changed,
                                                fmi3Boolean* next_event_time_defined,
                                                fmi3Float64* next_event_time);

/* FMU state (canGetAndSetFMUState, canSerializeFMUState) */
typedef fmi3Status fmi3GetFMUStateTYPE(fmi3Instance instance, fmi3FMUState* state);
typedef fmi3Status fmi3SetFMUStateTYPE(fmi3Instance instance, fmi3FMUState state);
typedef fmi3Status fmi3FreeFMUStateTYPE(fmi3Instance instance, fmi3FMUState* state);
typedef fmi3Status fmi3SerializedFMUStateSizeTYPE(fmi3Instance instance, fmi3FMUState state, size_t* size);
typedef fmi3Status fmi3SerializeFMUStateTYPE(fmi3Instance instance, fmi3FMUState state, fmi3Byte serialized[],
                                             size_t size);
typedef fmi3Status fmi3DeserializeFMUStateTYPE(fmi3Instance instance, const fmi3Byte serialized[], size_t size,
                                               fmi3FMUState* state);

/* Model Exchange */
typedef fmi3Status fmi3EnterContinuousTimeModeTYPE(fmi3Instance instance);
typedef fmi3Status fmi3CompletedIntegratorStepTYPE(fmi3Instance instance, fmi3Boolean no_set_fmu_state_prior,
                                                   fmi3Boolean* enter_event_mode,
                                                   fmi3Boolean* terminate_simulation);
typedef fmi3Status fmi3SetTimeTYPE(fmi3Instance instance, fmi3Float64 time);
typedef fmi3Status fmi3SetContinuousStatesTYPE(fmi3Instance instance, const fmi3Float64 x[], size_t nx);
typedef fmi3Status fmi3GetContinuousStateDerivativesTYPE(fmi3Instance instance, fmi3Float64 derivatives[],
                                                         size_t nx);
typedef fmi3Status fmi3GetEventIndicatorsTYPE(fmi3Instance instance, fmi3Float64 indicators[], size_t ni);
typedef fmi3Status fmi3GetContinuousStatesTYPE(fmi3Instance instance, fmi3Float64 x[], size_t nx);

/* Co-Simulation */
typedef fmi3Status fmi3DoStepTYPE(fmi3Instance instance, fmi3Float64 current_communication_point,
                                  fmi3Float64 communication_step_size, fmi3Boolean no_set_fmu_state_prior,
                                  fmi3Boolean* event_handling_needed, fmi3Boolean* terminate_simulation,
                                  fmi3Boolean* early_return, fmi3Float64* last_successful_time);

#ifdef __cplusplus
}
#endif

#endif
