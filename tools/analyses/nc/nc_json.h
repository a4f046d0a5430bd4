// The NC analyses as JSON (layouts in docs/nc-analyses.md): schema_version, command,
// provenance, the scene and the data source, then flat snake_case keys with the unit as
// suffix (frequencies in Hz, lengths in mm), sweeps as arrays of objects.
#pragma once

#include <nlohmann/json.hpp>

#include "motor_bode.h"
#include "slide_modes.h"

namespace mechsim::tools::nc_analyses {

// Values that do not exist (no resonance of an overdamped shaft mode) are null.
// Throw std::runtime_error when the scene file cannot be read for its hash.
nlohmann::json motor_bode_json(const MotorBodeResult& result);
nlohmann::json slide_modes_json(const SlideModesResult& result);

}  // namespace mechsim::tools::nc_analyses
