// The FMI 2.0 and 3.0 implementations of FmuInstance (one file each).
#pragma once

#include <memory>
#include <string>

#include "mechsim/fmi/instance.h"

namespace mechsim::fmi {

std::unique_ptr<FmuInstance> make_fmi2_instance(const FmuArchive& archive, InterfaceKind kind,
                                                const std::string& instance_name);
std::unique_ptr<FmuInstance> make_fmi3_instance(const FmuArchive& archive, InterfaceKind kind,
                                                const std::string& instance_name);

}  // namespace mechsim::fmi
