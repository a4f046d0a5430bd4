// What the FMI 3.0 entry points of an exported participant share (fmi3_entry.cpp,
// fmi3_unsupported.cpp): the export attribute and the refusal of a function it does not offer.
#pragma once

#include "mechsim/fmi/fmi3_functions.h"

#define MECHSIM_FMI_EXPORT extern "C" __attribute__((visibility("default")))

namespace mechsim::fmi_export {

// Logs "<function> is not supported: <why>" through the instance's logger; fmi3Error.
fmi3Status fmi3_unsupported(fmi3Instance instance, const char* function, const char* why);

}  // namespace mechsim::fmi_export
