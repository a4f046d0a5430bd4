#include "commands.h"
#include "scene_override.h"

namespace mechsim::tools {

void add_scene_args(CLI::App* cmd, SceneArgs& a) {
  cmd->add_option("scene", a.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", a.sets,
                  "override a scene value, repeatable: 'time.end=4 s', or '<participant>.<param>=<value>' "
                  "as short for participants.<participant>.params.<param>");
  cmd->add_option("--step", a.step, "macro step, e.g. '0.5 ms' (time.step)");
  cmd->add_option("--end", a.end, "end time, e.g. '4 s' (time.end)");
  cmd->add_option("--mode", a.mode, "lockstep | realtime (mode)");
  cmd->add_option("--rtf", a.rtf, "real-time factor (rtf)");
}

std::vector<std::string> SceneArgs::overrides() const {
  std::vector<std::string> out;
  for (const auto& s : sets) out.push_back(scene_override(s));
  if (!step.empty()) out.push_back("time.step=" + step);
  if (!end.empty()) out.push_back("time.end=" + end);
  if (!mode.empty()) out.push_back("mode=" + mode);
  if (!rtf.empty()) out.push_back("rtf=" + rtf);
  return out;
}

}  // namespace mechsim::tools
