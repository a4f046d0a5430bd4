// What to change when a run diverged: the connections across a coupling element (else the
// diverged node's own) and a smaller macro step, the stable one found by in-process runs of
// the resolved scene where a search is possible (libs/assess stable_step.h). Called once the run is
// over, by the report, never from inside the supervision.
#pragma once

#include <string>

#include "mechsim/config/scene.h"

namespace mechsim::launch {

// ". The coupled run is unstable ...; try ..." (appended to the failure reason).
std::string divergence_advice(const config::Scene& scene, const std::string& resolved_scene_path, const std::string& node);

}  // namespace mechsim::launch
