// Factory for the transport backends compiled into this build.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mechsim/transport/participant.h"
#include "mechsim/transport/security.h"

namespace mechsim::transport {

// Backends compiled in, e.g. {"cyclone"}.
std::vector<std::string> available_vendors();

// Creates the process's participant on a DDS domain. Throws std::runtime_error naming the
// vendor when it is not compiled in or the participant cannot be created. "inproc" (always
// built; not in available_vendors(): it connects only the participants of one process)
// gives a participant of an in-process domain: a scene's nodes as threads (inproc_run.h).
// Secured (docs/security.md) when MECHSIM_DDS_SECURITY and MECHSIM_DDS_IDENTITY are set
// (security_from_environment()), the launcher's way of handing a process its identity.
std::unique_ptr<Participant> create_participant(const std::string& vendor, int domain_id);
// The same with an explicit identity (nullopt: unsecured, whatever the environment says).
std::unique_ptr<Participant> create_participant(const std::string& vendor, int domain_id,
                                                const std::optional<SecurityIdentity>& security);

// A participant for a member of a process group (docs/scenes.md), secured as
// create_participant(vendor, domain_id). On Fast DDS every such participant of the process
// on the same domain uses one DomainParticipant: one set of threads, ports and discovery
// for the process instead of one per member (docs/performance.md); each member keeps its
// own endpoints and its own wait()/wake(). Cyclone DDS already runs all participants of a
// process on one domain instance (one set of threads and sockets), so there, and in
// process, it is create_participant().
std::unique_ptr<Participant> create_group_member_participant(const std::string& vendor, int domain_id);

// Removes what killed processes of any backend left on this host (Fast DDS: its
// shared-memory transport's segments). Leaves live processes' resources alone, so it is
// safe while other runs go on.
void clean_up_after_killed_processes();

}  // namespace mechsim::transport
