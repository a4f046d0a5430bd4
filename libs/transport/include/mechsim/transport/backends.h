// Factory for the transport backends compiled into this build.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mechsim/transport/participant.h"

namespace mechsim::transport {

// Backends compiled in, e.g. {"cyclone"}.
std::vector<std::string> available_vendors();

// Creates the process's participant on a DDS domain. Throws std::runtime_error naming the
// vendor when it is not compiled in or the participant cannot be created.
std::unique_ptr<Participant> create_participant(const std::string& vendor, int domain_id);

// Removes what the backends may leave on this host after a run on `domain_id`, once all of
// its processes have exited, killed ones included (Fast DDS: shared-memory segments).
void clean_up_domain(int domain_id);

}  // namespace mechsim::transport
