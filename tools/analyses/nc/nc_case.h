// Where the NC analyses take their data from, parsed with the node types' own parsers
// (mechsim/catalog/nc_params.h) so that a scene means the same to a time run and to the
// analyses:
//   motor  the first `tachometer` participant's params; else design.motor; else the spec's
//          identified set (nc_slide.md §1).
//   slide  the first `slide` participant's params, with the coupling stiffness C_kopp of the
//          connection element (`coupling:`) to or from it when there is one (that is the
//          spring the time run uses); else design.slide; else the CNC 200 defaults with
//          I_slide = m s²/4π².
// Data in both a participant and the design section is refused as ambiguous.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/models/nc/motor_tacho.h"
#include "mechsim/models/nc/slide_drive_data.h"
#include "nc_design_settings.h"

namespace mechsim::tools::nc_analyses {

struct DataSource {
  std::string kind;   // "participant" | "design" | "defaults"
  std::string where;  // key path: "participants.motor.params", "design.motor"; "" for defaults
};

struct MotorCase {
  models::nc::MotorTachoParams params;
  DataSource source;
  std::vector<std::string> notes;  // e.g. "2 tachometer participants: the first ('x') is analysed"
};

struct SlideCase {
  models::nc::SlideDriveData data;
  DataSource source;
  DataSource coupling_stiffness_source;  // the connection's `coupling:`, the params, or defaults
  std::vector<std::string> notes;
};

// Throw config::ConfigError naming the file and key path.
MotorCase motor_case_from_scene(const config::Scene& scene, const NcDesignSettings& settings);
SlideCase slide_case_from_scene(const config::Scene& scene, const NcDesignSettings& settings);

}  // namespace mechsim::tools::nc_analyses
