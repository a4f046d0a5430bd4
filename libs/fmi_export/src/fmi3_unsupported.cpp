// The FMI 3.0 functions of interfaces and types an exported participant does not offer:
// FMI 3.0.2 (§2.2) requires an FMU's binary to export every function of fmi3Functions.h,
// and importers (FMPy) resolve them all when loading it. Each logs why and returns
// fmi3Error. The FMU's own functions: fmi3_entry.cpp. tests/unit/fmi_export checks the
// binary against the standard's list (fmi3_function_names.txt).
#include <cstddef>
#include <cstdint>

#include "fmi3_export.h"

namespace {

// The standard's types these functions take, as fmi3PlatformTypes.h defines them.
using fmi3Float32 = float;
using fmi3Int8 = std::int8_t;
using fmi3UInt8 = std::uint8_t;
using fmi3Int16 = std::int16_t;
using fmi3UInt16 = std::uint16_t;
using fmi3UInt32 = std::uint32_t;
using fmi3Int64 = std::int64_t;
using fmi3UInt64 = std::uint64_t;
using fmi3Binary = const fmi3Byte*;
using fmi3Clock = bool;
enum fmi3IntervalQualifier { fmi3IntervalNotYetKnown, fmi3IntervalUnchanged, fmi3IntervalChanged };
enum fmi3DependencyKind { fmi3Independent, fmi3Constant, fmi3Fixed, fmi3Tunable, fmi3Discrete, fmi3Dependent };

using mechsim::fmi_export::fmi3_unsupported;
fmi3Status unsupported(fmi3Instance c, const char* function, const char* why) { return fmi3_unsupported(c, function, why); }

}  // namespace

// fmi3Get<Type> and fmi3Set<Type> of a variable type the FMU has none of.
#define MECHSIM_FMI3_NO_VARIABLES_OF(Name, Type)                                                                  \
  MECHSIM_FMI_EXPORT fmi3Status fmi3Get##Name(fmi3Instance c, const fmi3ValueReference[], size_t, Type[], size_t) {     \
    return unsupported(c, "fmi3Get" #Name, "the FMU has no " #Name " variables (its variables are Float64)");          \
  }                                                                                                                 \
  MECHSIM_FMI_EXPORT fmi3Status fmi3Set##Name(fmi3Instance c, const fmi3ValueReference[], size_t, const Type[], size_t) { \
    return unsupported(c, "fmi3Set" #Name, "the FMU has no " #Name " variables (its variables are Float64)");          \
  }

MECHSIM_FMI3_NO_VARIABLES_OF(Float32, fmi3Float32)
MECHSIM_FMI3_NO_VARIABLES_OF(Int8, fmi3Int8)
MECHSIM_FMI3_NO_VARIABLES_OF(UInt8, fmi3UInt8)
MECHSIM_FMI3_NO_VARIABLES_OF(Int16, fmi3Int16)
MECHSIM_FMI3_NO_VARIABLES_OF(UInt16, fmi3UInt16)
MECHSIM_FMI3_NO_VARIABLES_OF(UInt32, fmi3UInt32)
MECHSIM_FMI3_NO_VARIABLES_OF(Int64, fmi3Int64)
MECHSIM_FMI3_NO_VARIABLES_OF(UInt64, fmi3UInt64)
MECHSIM_FMI3_NO_VARIABLES_OF(String, fmi3String)

MECHSIM_FMI_EXPORT fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference, fmi3Float64) {
  return unsupported(c, "fmi3ActivateModelPartition", "the FMU offers no scheduled execution");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean, fmi3Boolean*, fmi3Boolean*) {
  return unsupported(c, "fmi3CompletedIntegratorStep", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3EnterConfigurationMode(fmi3Instance c) {
  return unsupported(c, "fmi3EnterConfigurationMode", "the FMU has no structural parameters");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance c) {
  return unsupported(c, "fmi3EnterContinuousTimeMode", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) {
  return unsupported(c, "fmi3EvaluateDiscreteStates", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3ExitConfigurationMode(fmi3Instance c) {
  return unsupported(c, "fmi3ExitConfigurationMode", "the FMU has no structural parameters");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference[], size_t, size_t[], fmi3Binary[], size_t) {
  return unsupported(c, "fmi3GetBinary", "the FMU has no Binary variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Clock[]) {
  return unsupported(c, "fmi3GetClock", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance c, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetContinuousStateDerivatives", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetContinuousStates(fmi3Instance c, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetContinuousStates", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetEventIndicators(fmi3Instance c, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetEventIndicators", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Float64[], fmi3IntervalQualifier[]) {
  return unsupported(c, "fmi3GetIntervalDecimal", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt64[], fmi3UInt64[], fmi3IntervalQualifier[]) {
  return unsupported(c, "fmi3GetIntervalFraction", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance c, fmi3Float64[], size_t) {
  return unsupported(c, "fmi3GetNominalsOfContinuousStates", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t*) {
  return unsupported(c, "fmi3GetNumberOfContinuousStates", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t*) {
  return unsupported(c, "fmi3GetNumberOfEventIndicators", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference, size_t*) {
  return unsupported(c, "fmi3GetNumberOfVariableDependencies", "the dependencies are those of <ModelStructure>");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetShiftDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Float64[]) {
  return unsupported(c, "fmi3GetShiftDecimal", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetShiftFraction(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt64[], fmi3UInt64[]) {
  return unsupported(c, "fmi3GetShiftFraction", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference, size_t[], fmi3ValueReference[], size_t[], fmi3DependencyKind[], size_t) {
  return unsupported(c, "fmi3GetVariableDependencies", "the dependencies are those of <ModelStructure>");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference[], size_t, const size_t[], const fmi3Binary[], size_t) {
  return unsupported(c, "fmi3SetBinary", "the FMU has no Binary variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Clock[]) {
  return unsupported(c, "fmi3SetClock", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetContinuousStates(fmi3Instance c, const fmi3Float64[], size_t) {
  return unsupported(c, "fmi3SetContinuousStates", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetIntervalDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Float64[]) {
  return unsupported(c, "fmi3SetIntervalDecimal", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetIntervalFraction(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt64[], const fmi3UInt64[]) {
  return unsupported(c, "fmi3SetIntervalFraction", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetShiftDecimal(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Float64[]) {
  return unsupported(c, "fmi3SetShiftDecimal", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetShiftFraction(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt64[], const fmi3UInt64[]) {
  return unsupported(c, "fmi3SetShiftFraction", "the FMU has no clocks and no event mode");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64) {
  return unsupported(c, "fmi3SetTime", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Float64*) {
  return unsupported(c, "fmi3UpdateDiscreteStates", "the FMU has no clocks and no event mode");
}
