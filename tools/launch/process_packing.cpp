#include "process_packing.h"

#include <sched.h>

#include <algorithm>
#include <map>
#include <thread>

namespace mechsim::launch {

int usable_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  return std::max(1u, std::thread::hardware_concurrency());
}

std::vector<std::string> process_packing_overrides(const config::Scene& scene, int cores) {
  if (!scene.processes.packs()) return {};
  const config::ConfigNode participants = scene.root.child("participants");
  // Packed participants by vendor and restart policy, in scene order.
  std::map<std::pair<std::string, bool>, std::vector<std::string>> packable;
  for (const auto& p : scene.participants) {
    // Those a group cannot hold (check_process_groups) or that chose their own process.
    if (!p.process.empty() || !p.host.empty() || participants.child(p.name).has("realtime")) continue;
    packable[{p.vendor, p.restart}].push_back(p.name);
  }
  const int per_vendor = scene.processes.kind == config::ProcessLayout::Kind::per_core ? cores : scene.processes.count;
  std::map<std::string, int> groups_of_vendor;  // numbering across restart policies
  std::vector<std::string> out;
  for (const auto& [key, names] : packable) {
    const int n = static_cast<int>(names.size());
    const int groups = std::clamp(per_vendor, 1, n);
    const int first = groups_of_vendor[key.first] + 1;
    groups_of_vendor[key.first] += groups;
    // Contiguous, sizes differing by at most one: member i goes to group i * groups / n.
    for (int i = 0; i < n; ++i)
      out.push_back("participants." + names[i] + ".process=auto_" + key.first + "_" + std::to_string(first + i * groups / n));
  }
  return out;
}

}  // namespace mechsim::launch
