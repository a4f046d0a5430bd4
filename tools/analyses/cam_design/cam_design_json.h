// The cam design report as JSON (layout in docs/cam-design.md): schema_version,
// provenance, the scene, then flat snake_case keys with the unit as suffix, per-segment
// values as an array of objects.
#pragma once

#include <nlohmann/json.hpp>

#include "cam_design_report.h"

namespace mechsim::tools::cam_design {

// Infinite values (no convex part on a segment, a follower that never lifts off) are null.
// Throws std::runtime_error when the scene file cannot be read for its hash.
nlohmann::json report_json(const CamDesignResult& result);

// An angle of the cycle in [0, 360) deg; null when not finite (the sweep's JSON too).
nlohmann::json cycle_deg(double rad);

}  // namespace mechsim::tools::cam_design
