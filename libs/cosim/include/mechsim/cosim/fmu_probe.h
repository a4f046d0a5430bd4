// A scene's FMUs instantiated away from the process that plans the run (docs/fmi.md, "Where
// FMU code runs"): the launcher and `mechsim check` build their plan with FMU blocks that
// instantiate at first use, and have each FMU instantiated and initialized, with the scene's
// parameters, by a child process (`mechsim fmu probe`, tools/fmu/fmu_probe.h), so that an
// FMU that aborts or crashes there takes the child down, not them.
#pragma once

#include <string>
#include <vector>

#include "mechsim/cosim/scene_plan.h"

namespace mechsim::cosim {

struct PlannedFmu {
  std::string participant;
  std::string file;  // resolved against the scene's folder
};
// The plan's participants played by an FMU (type fmu, or an FMU in place of a native block).
std::vector<PlannedFmu> planned_fmus(const ScenePlan& plan);

// From now on this process's FMU blocks instantiate at their first use, not when made.
void defer_fmu_instantiation();

// The probe child: loads, instantiates and initializes the FMU of `participant` now.
// Throws config::ConfigError naming the scene's key, as building the plan in a node would.
void instantiate_fmu(const ScenePlan& plan, const std::string& participant);

}  // namespace mechsim::cosim
