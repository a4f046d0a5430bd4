// What `mechsim fmu info` prints about an FMU: version, interfaces with their capability
// flags, variables (causality, variability, type, unit, start), platforms in the archive and
// whether this host can run it, as a table for people and as JSON for scripts.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "mechsim/fmi/archive.h"

namespace mechsim::tools {

std::string format_fmu_info(const fmi::FmuArchive& archive);
nlohmann::json fmu_info_json(const fmi::FmuArchive& archive);

}  // namespace mechsim::tools
