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
MECHSIM_FMI_EXPORT fmi3Status fmi3GetFloat32(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Float32[], size_t) {
  return unsupported(c, "fmi3GetFloat32", "the FMU has no Float32 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetInt16(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Int16[], size_t) {
  return unsupported(c, "fmi3GetInt16", "the FMU has no Int16 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetInt64(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Int64[], size_t) {
  return unsupported(c, "fmi3GetInt64", "the FMU has no Int64 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetInt8(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3Int8[], size_t) {
  return unsupported(c, "fmi3GetInt8", "the FMU has no Int8 variables (its variables are Float64)");
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
MECHSIM_FMI_EXPORT fmi3Status fmi3GetString(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3String[], size_t) {
  return unsupported(c, "fmi3GetString", "the FMU has no String variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetUInt16(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt16[], size_t) {
  return unsupported(c, "fmi3GetUInt16", "the FMU has no UInt16 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetUInt32(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt32[], size_t) {
  return unsupported(c, "fmi3GetUInt32", "the FMU has no UInt32 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetUInt64(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt64[], size_t) {
  return unsupported(c, "fmi3GetUInt64", "the FMU has no UInt64 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3GetUInt8(fmi3Instance c, const fmi3ValueReference[], size_t, fmi3UInt8[], size_t) {
  return unsupported(c, "fmi3GetUInt8", "the FMU has no UInt8 variables (its variables are Float64)");
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
MECHSIM_FMI_EXPORT fmi3Status fmi3SetFloat32(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Float32[], size_t) {
  return unsupported(c, "fmi3SetFloat32", "the FMU has no Float32 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetInt16(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Int16[], size_t) {
  return unsupported(c, "fmi3SetInt16", "the FMU has no Int16 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetInt64(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Int64[], size_t) {
  return unsupported(c, "fmi3SetInt64", "the FMU has no Int64 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetInt8(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3Int8[], size_t) {
  return unsupported(c, "fmi3SetInt8", "the FMU has no Int8 variables (its variables are Float64)");
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
MECHSIM_FMI_EXPORT fmi3Status fmi3SetString(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3String[], size_t) {
  return unsupported(c, "fmi3SetString", "the FMU has no String variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64) {
  return unsupported(c, "fmi3SetTime", "the FMU offers co-simulation only (no <ModelExchange>)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetUInt16(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt16[], size_t) {
  return unsupported(c, "fmi3SetUInt16", "the FMU has no UInt16 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetUInt32(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt32[], size_t) {
  return unsupported(c, "fmi3SetUInt32", "the FMU has no UInt32 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetUInt64(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt64[], size_t) {
  return unsupported(c, "fmi3SetUInt64", "the FMU has no UInt64 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3SetUInt8(fmi3Instance c, const fmi3ValueReference[], size_t, const fmi3UInt8[], size_t) {
  return unsupported(c, "fmi3SetUInt8", "the FMU has no UInt8 variables (its variables are Float64)");
}
MECHSIM_FMI_EXPORT fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Float64*) {
  return unsupported(c, "fmi3UpdateDiscreteStates", "the FMU has no clocks and no event mode");
}
