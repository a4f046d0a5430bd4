// Scene parser + validator, as `mechsim check` runs them (tools/mechsim/cmd_check.cpp):
// load_scene (YAML, units such as "25 mm", "30 rpm", "45 deg") then ScenePlan::build (the
// catalog's node types, their params, connections). Input: the YAML text of a scene.
// A ConfigError is the expected refusal of bad input; anything else escaping (another
// exception type, which `mechsim check` would not catch), a crash, UB or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz_input_file.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"

namespace {

std::vector<std::string> small_cvt_tables(const mechsim::config::Scene& scene) {
  std::vector<std::string> overrides;
  for (const auto& p : scene.participants) {
    if (p.type != "cvt" || !p.params.is_map()) continue;
    const std::string params = "participants." + p.name + ".params.";
    overrides.push_back(params + "shape_table.points=3");
    const auto belt_map = p.params.optional_child("belt_map");
    if (!belt_map || belt_map->is_map())
      for (const char* axis : {"s_points", "torque_points", "speed_points"})
        overrides.push_back(params + "belt_map." + axis + "=2");
    else if (belt_map->is_scalar() && belt_map->as_string() != "direct")
      overrides.push_back(params + "belt_map=direct");  // "table" at its default size
  }
  return overrides;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const mechsim::fuzz::ScratchFile scene_file(".yaml");
  scene_file.write(data, size);
  try {
    mechsim::config::Scene scene = mechsim::config::load_scene(scene_file.path());
    // A cvt participant tabulates its belt map and shape when built (330 + 101 solutions of
    // the belt model by default: 0.5 s optimised, about 9 s under the sanitizers), by design
    // and within the point counts its validation allows. The harness shrinks those tables
    // through the scene's own override path, so that an input costs milliseconds and its
    // parameters are still validated (belt_map: table becomes direct).
    if (const auto overrides = small_cvt_tables(scene); !overrides.empty())
      scene = mechsim::config::load_scene(scene_file.path(), overrides);
    const mechsim::cosim::ScenePlan plan = mechsim::cosim::ScenePlan::build(scene);
    (void)plan.nodes().size();
    (void)mechsim::config::scene_to_yaml(scene);
  } catch (const mechsim::config::ConfigError& e) {
    // The refusal must say something (file and what was expected).
    if (e.what()[0] == '\0') std::abort();
  }
  return 0;
}
