// Scene parser + validator, as `mechsim check` runs them (tools/mechsim/cmd_check.cpp):
// load_scene (YAML, units such as "25 mm", "30 rpm", "45 deg") then ScenePlan::build (the
// catalog's node types, their params, connections). Input: the YAML text of a scene.
// A ConfigError is the expected refusal of bad input; anything else escaping (another
// exception type, which `mechsim check` would not catch), a crash, UB or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>

#include "fuzz_input_file.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const mechsim::fuzz::ScratchFile scene_file(".yaml");
  scene_file.write(data, size);
  try {
    const mechsim::config::Scene scene = mechsim::config::load_scene(scene_file.path());
    const mechsim::cosim::ScenePlan plan = mechsim::cosim::ScenePlan::build(scene);
    (void)plan.nodes().size();
    (void)mechsim::config::scene_to_yaml(scene);
  } catch (const mechsim::config::ConfigError& e) {
    // The refusal must say something (file and what was expected).
    if (e.what()[0] == '\0') std::abort();
  }
  return 0;
}
