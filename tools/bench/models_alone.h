// `mechsim bench SCENE --models-alone` (issue 42 item 5): the floor of a scene's stepping
// cost, its node steppers called in a loop on one thread with no transport (the
// product's NodeSteppers in plan order, samples handed to the readers' input channels in
// memory: cosim::SteppedRun). No thread hand-off, no serialization, no output log: what a
// co-simulation master cannot go below with these models. tools/bench-peer.sh runs it next
// to `mechsim launch` and libcosim (docs/performance.md "Against a peer: libcosim").
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace mechsim::bench {

struct ModelsAloneOptions {
  std::vector<std::string> set_overrides;
  std::string json_path;  // one JSON document with the figures; empty: none
};

// Prints "models alone: N steps in W s wall, C s CPU: S steps/s ..."; returns the exit code
// (0 done, 1 the run failed or diverged, 2 a scene the plan refuses).
int run_models_alone(const std::string& scene_path, const ModelsAloneOptions& options, std::ostream& out);

}  // namespace mechsim::bench
