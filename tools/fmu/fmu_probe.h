// `mechsim fmu probe`, and the parent's side of it (docs/fmi.md, "Where FMU code runs"):
// what `mechsim check` and `mechsim launch` learn by instantiating a scene's FMUs (that each
// loads, instantiates and initializes with the scene's parameters), learnt in a child
// process per FMU, so that an FMU that aborts or crashes there is reported with its file
// and the signal instead of taking the launcher down.
#pragma once

#include <string>
#include <vector>

#include "mechsim/cosim/scene_plan.h"

namespace mechsim::tools {

// The child: builds the plan of `scene_file` with `overrides`, FMUs unpacked under
// `unpack_dir` ("" = the temporary directory), instantiates `participant`'s FMU and prints
// {"participant", "file", "ok", "error"} as JSON on stdout. Returns the exit code (0 ok,
// 1 the FMU refused, 2 a bad scene).
int run_fmu_probe(const std::string& scene_file, const std::vector<std::string>& overrides, const std::string& participant,
                  const std::string& unpack_dir);

// The parent: a `mechsim fmu probe` child for each FMU of `plan` (of `scene_file` with
// `overrides`), one after the other; "" when all instantiated, else what went wrong, naming
// the FMU's file, its participant and how the child ended. The FMUs unpack under
// `unpack_dir` ("": a temporary folder of this call's, removed when it returns).
std::string probe_fmus_in_children(const std::string& scene_file, const std::vector<std::string>& overrides,
                                   const cosim::ScenePlan& plan, const std::string& unpack_dir);

}  // namespace mechsim::tools
