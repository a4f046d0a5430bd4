// `processes: per_core | N` (docs/scenes.md#processes-per-participant-or-per-core): which
// participants of the launcher's host the launcher packs into process groups, and into which.
// Many participants on few cores cost more CPU per participant-step when each is a process
// of its own (a context switch among more processes costs more, docs/performance.md); a few
// process groups keep that cost flat.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/scene.h"

namespace mechsim::launch {

// The cores this process may run on (its CPU affinity), at least 1.
int usable_cores();

// A participant the launcher puts into a process group, and which.
struct PackedParticipant {
  std::string participant;
  std::string group;
};

// processes: auto (the default) on a scene whose participants all run on the launcher's
// host, unsecured: one group per DDS vendor (a second per core only past 8 participants),
// FMU participants each in a process of their own; on several hosts or secured: a process
// per participant.
// The process groups that lay the scene out as its `processes:` asks, `cores` being the
// launcher's host's (taken for every host: the launcher cannot see the others';
// `processes: N` says it for all); none for per_participant. Packed are the
// participants without `process:` or a `realtime:` of their own; each host and DDS vendor
// gets its own groups (`auto_<vendor>_<i>` on the launcher's host, `auto_<host>_<vendor>_<i>`
// on another, i from 1), the participants of one restart policy together, and neighbours
// in scene order share a group (scenes list partners side by side: a cam and its follower),
// so most samples stay inside a process. Groups per host and vendor: `cores` (per_core) or
// the scene's count, never more than the participants packed.
std::vector<PackedParticipant> pack_processes(const config::Scene& scene, int cores);

}  // namespace mechsim::launch
