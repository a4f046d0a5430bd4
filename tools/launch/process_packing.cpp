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

namespace {

using Kind = config::ProcessLayout::Kind;

// processes: auto on one host, unsecured: a group per vendor holds this many participants
// before a second core is used (measured: docs/performance.md "One executor per process").
constexpr int kParticipantsPerAutoGroup = 8;

// processes: auto packs only a scene whose every participant runs on the launcher's host
// and that is not secured (a secured participant's identity reaches it through its own
// process's environment): there one process per vendor is the fastest layout.
bool auto_packs(const config::Scene& scene) {
  if (!scene.security_dir.empty()) return false;
  return std::none_of(scene.participants.begin(), scene.participants.end(),
                      [](const config::ParticipantSpec& p) { return !p.host.empty(); });
}

// Groups per host and vendor for `n` packed participants.
int groups_for(const config::ProcessLayout& layout, int cores, int n) {
  if (layout.kind == Kind::per_core) return cores;
  if (layout.kind == Kind::count) return layout.count;
  return std::min(cores, (n + kParticipantsPerAutoGroup - 1) / kParticipantsPerAutoGroup);
}

}  // namespace

std::vector<PackedParticipant> pack_processes(const config::Scene& scene, int cores) {
  const bool automatic = scene.processes.kind == Kind::automatic;
  if (!scene.processes.packs() && !(automatic && auto_packs(scene))) return {};
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
    // By default an FMU keeps a process of its own: a user's model that crashes or exits
    // takes only itself down (docs/fmi.md).
    if (automatic && p.type == "fmu") continue;
    const Key key{p.host, p.vendor, p.restart};
    if (!packable.contains(key)) order.push_back(key);
    packable[key].push_back(p.name);
  }
  std::map<std::pair<std::string, std::string>, int> groups_so_far;  // (host, vendor) -> groups numbered
  std::vector<PackedParticipant> out;
  for (const Key& key : order) {
    const std::vector<std::string>& names = packable[key];
    const int n = static_cast<int>(names.size());
    if (automatic && n == 1) continue;  // a group of one would be a node process under another name
    const int groups = std::clamp(groups_for(scene.processes, cores, n), 1, n);
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
