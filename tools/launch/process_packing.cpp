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

std::vector<PackedParticipant> pack_processes(const config::Scene& scene, int cores) {
  if (!scene.processes.packs()) return {};
  const config::ConfigNode participants = scene.root.child("participants");
  // Packed participants by host, vendor and restart policy, in scene order.
  struct Key {
    std::string host, vendor;
    bool restart;
    auto operator<=>(const Key&) const = default;
  };
  std::map<Key, std::vector<std::string>> packable;
  std::vector<Key> order;  // keys as first met, so group numbers follow the scene
  for (const auto& p : scene.participants) {
    // Those that chose their own process, or whose own realtime: is a process's setting.
    if (!p.process.empty() || participants.child(p.name).has("realtime")) continue;
    const Key key{p.host, p.vendor, p.restart};
    if (!packable.contains(key)) order.push_back(key);
    packable[key].push_back(p.name);
  }
  const int per_vendor = scene.processes.kind == config::ProcessLayout::Kind::per_core ? cores : scene.processes.count;
  std::map<std::pair<std::string, std::string>, int> groups_so_far;  // (host, vendor) -> groups numbered
  std::vector<PackedParticipant> out;
  for (const Key& key : order) {
    const std::vector<std::string>& names = packable[key];
    const int n = static_cast<int>(names.size());
    const int groups = std::clamp(per_vendor, 1, n);
    int& numbered = groups_so_far[{key.host, key.vendor}];
    const int first = numbered + 1;
    numbered += groups;
    const std::string prefix = "auto_" + (key.host.empty() ? "" : key.host + "_") + key.vendor + "_";
    // Contiguous, sizes differing by at most one: member i goes to group i * groups / n.
    for (int i = 0; i < n; ++i)
      out.push_back({names[i], prefix + std::to_string(first + i * groups / n)});
  }
  return out;
}

}  // namespace mechsim::launch
