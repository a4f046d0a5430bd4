// What `--set` takes, as the scene loader takes it: "time.end=4 s" stays as it is, and
// "<participant>.<param>=<value>" is short for "participants.<participant>.params.<param>=<value>".
// One rule for every command that sets scene keys (`mechsim launch` and the other scene
// commands, `mechsim sweep --vary`, the Python package).
#pragma once

#include <string>

namespace mechsim::tools {

// "KEY=VALUE" (or a bare KEY) with KEY spelled out as the scene loader's dotted path.
std::string scene_override(const std::string& set);

}  // namespace mechsim::tools
