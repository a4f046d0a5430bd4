// The scene as a bench read it, for all of the bench's runs: a copy (the resolved scene,
// --set overrides applied, as `mechsim launch` hands its nodes the run folder's copy) in a
// folder of its own, removed with the object. A bench loads its scene for every run,
// thousands of times over minutes; loaded from the user's file, a run that came while the
// file was being saved (an editor writes it anew) read a half-written scene ("'connections'
// is not a list") or another scene than the one the bench's table names.
#pragma once

#include <string>

#include "mechsim/config/scene.h"

namespace mechsim::bench {

class SceneSnapshot {
 public:
  // Throws std::runtime_error naming the folder or file it cannot write.
  explicit SceneSnapshot(const config::Scene& scene);
  ~SceneSnapshot();
  SceneSnapshot(const SceneSnapshot&) = delete;
  SceneSnapshot& operator=(const SceneSnapshot&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string dir_, path_;
};

}  // namespace mechsim::bench
