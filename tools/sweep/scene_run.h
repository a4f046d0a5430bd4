// One full run of a scene in this process, the way `mechsim bench` runs its points
// (cosim::run_inproc: every node on an executor thread of this process, over the in-process
// transport, bit for bit the numbers of a DDS run), then measured against the monolithic
// reference as `mechsim launch` measures a run (assess::compare_with_reference: every
// compared signal's error, the reference's own accuracy, the report figures). Shared by a
// sweep's points and the Python package's mechsim.run().
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/assess/reference_comparison.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/inproc_run.h"

namespace mechsim::sweep {

struct SceneRun {
  std::string outcome = "refused";  // ok, diverged (a node's guard, or non-finite errors), failed, refused
  std::string reason;               // why, when not ok
  long steps = 0;                   // macro steps taken (at the failure: the step it failed at)
  double wall_time_s = 0;           // the whole point: scene, run and comparison
  double run_wall_time_s = 0;       // the nodes' run alone
  std::unique_ptr<config::Scene> scene;  // set unless the scene was refused
  cosim::InprocRunResult inproc;
  std::optional<assess::ReferenceComparison> comparison;  // set when every node ran to the end
};

// Loads `scene_path` with `overrides` (dotted keys, as config::load_scene takes them), runs
// it into `run_dir` (created) and compares. Never throws for a scene or run problem: those
// are the outcome and its reason.
SceneRun run_scene(const std::string& scene_path, const std::vector<std::string>& overrides, const std::string& run_dir);

}  // namespace mechsim::sweep
