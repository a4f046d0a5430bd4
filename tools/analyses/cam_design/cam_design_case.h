// The roller-follower design case of a scene: the first `cam_shaft` participant (law, R0,
// e, speed) and the first `follower` participant (mass, spring, loads, roller radius),
// parsed with the node types' own parsers so that a scene means the same to a time run
// and to the analysis.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "cam_design_settings.h"
#include "mechsim/config/scene.h"
#include "mechsim/models/cam/design.h"

namespace mechsim::tools::cam_design {

// The span of the first C1 matched to the C2 that follows it (spec §1: 2 L1/β1 = 2 L2/β2).
struct C1Match {
  std::size_t c1_law_index;     // index in the scene's `law:` list
  std::size_t c2_law_index;
  double matched_span_rad;      // β1 = β2 L1/L2
  double scene_span_rad;        // the span the scene gives the C1
  bool scene_span_matches;      // equal to within 1e-6 deg
};

struct RollerCase {
  std::string cam_participant;       // instance names used
  std::string follower_participant;
  std::vector<std::string> notes;    // e.g. "2 cam_shaft participants: the first ('cam') is analysed"
  models::cam::CamDesignInput input;
  std::vector<std::optional<std::size_t>> law_index;  // per law piece: index in `law:`, none for a filler dwell
  std::optional<C1Match> c1_match;   // when design.match_c1_to_c2
};

// Throws config::ConfigError (naming the file and key path) when a participant is missing
// or refused, or when the C1/C2 match is asked for a law without that pair.
RollerCase roller_case_from_scene(const config::Scene& scene, const DesignSettings& settings);

}  // namespace mechsim::tools::cam_design
