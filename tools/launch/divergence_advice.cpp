#include "divergence_advice.h"

#include <cstdio>
#include <optional>
#include <stdexcept>

#include "mechsim/assess/stable_step.h"

namespace mechsim::launch {

// Names the connections that cross a coupling element (instability travels round the
// loop, so the node that noticed it first need not sit at the cut), else the diverged
// node's own connections, and suggests a smaller macro step.
std::string divergence_advice(const config::Scene& scene, const std::string& resolved_scene_path, const std::string& node) {
  std::string cuts;
  for (const auto& c : scene.connections)
    if (c.coupling)
      cuts += (cuts.empty() ? "" : ", ") + c.from + " -> " + c.to + " (" + c.key_path + ", coupling element)";
  if (cuts.empty())
    for (const auto& c : scene.connections)
      if (c.from == node || c.to == node) cuts += (cuts.empty() ? "" : ", ") + c.from + " -> " + c.to + " (" + c.key_path + ")";
  char step[64], now[64];
  std::snprintf(step, sizeof step, "%g us", scene.time.step / 4 * 1e6);
  std::snprintf(now, sizeof now, "%g us", scene.time.step * 1e6);
  // An adaptive step lengthens its steps up to `max` as long as the estimate allows; a
  // stiff cut can be unstable long before its coupling error shows (docs/accuracy.md).
  if (scene.time.adaptive)
    return ". The coupled run is unstable with an adaptive step of up to " + std::string(now) + " across " + cuts +
           "; lower time.max, e.g. --set 'time.max=" + step + "' (a fixed step's stable limit: mechsim bench SCENE --stability)";
  // The stable step, found by in-process runs of the resolved scene (libs/assess stable_step.h),
  // halving the macro step; any sampled participant follows it.
  std::optional<double> stable;
  try {
    std::fprintf(stderr, "mechsim: the run diverged; looking for a stable macro step with in-process runs...\n");
    stable = assess::find_stable_step_below(resolved_scene_path, {}, scene.time.step);
  } catch (const std::exception&) {
    // No search possible (e.g. a replayed node): the generic advice below.
  }
  if (stable) {
    char found[64];
    std::snprintf(found, sizeof found, "%.4g us", *stable * 1e6);
    return ". The coupled run is unstable at a macro step of " + std::string(now) + " across " + cuts +
           "; in-process runs of this scene are stable at " + found + ": try --step '" + found +
           "' (mechsim bench SCENE --stability bisects the limit per scheme; docs/accuracy.md)";
  }
  return ". The coupled run is unstable at a macro step of " + std::string(now) + " across " + cuts + "; try a smaller step, e.g. --step '" + step +
         "' (docs/nc-loop.md lists the measured limits)";
}

}  // namespace mechsim::launch
