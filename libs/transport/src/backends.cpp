#include "mechsim/transport/backends.h"

#include <stdexcept>

#include "inproc/inproc_participant.h"

#ifdef MECHSIM_HAVE_CYCLONEDDS
#include "cyclone/cyclone_participant.h"
#endif
#ifdef MECHSIM_HAVE_FASTDDS
#include "fastdds/fastdds_participant.h"
#endif

namespace mechsim::transport {

std::vector<std::string> available_vendors() {
  std::vector<std::string> v;
#ifdef MECHSIM_HAVE_CYCLONEDDS
  v.push_back("cyclone");
#endif
#ifdef MECHSIM_HAVE_FASTDDS
  v.push_back("fastdds");
#endif
  return v;
}

std::unique_ptr<Participant> create_participant(const std::string& vendor, int domain_id) {
  // In-process participants never leave the process: nothing to secure.
  return create_participant(vendor, domain_id, vendor == "inproc" ? std::nullopt : security_from_environment());
}

std::unique_ptr<Participant> create_participant(const std::string& vendor, int domain_id,
                                                const std::optional<SecurityIdentity>& security) {
  if (vendor == "inproc") return std::make_unique<inproc::InprocParticipant>(domain_id);
#ifdef MECHSIM_HAVE_CYCLONEDDS
  if (vendor == "cyclone") return std::make_unique<cyclone::CycloneParticipant>(domain_id, security);
#endif
#ifdef MECHSIM_HAVE_FASTDDS
  if (vendor == "fastdds") return std::make_unique<fastdds::FastParticipant>(domain_id, security);
#endif
  throw std::runtime_error("DDS vendor '" + vendor + "' is not compiled into this build");
}

std::unique_ptr<Participant> create_group_member_participant(const std::string& vendor, int domain_id) {
#ifdef MECHSIM_HAVE_FASTDDS
  if (vendor == "fastdds") return std::make_unique<fastdds::FastParticipant>(domain_id, security_from_environment(), true);
#endif
  return create_participant(vendor, domain_id);
}

void clean_up_after_killed_processes() {
#ifdef MECHSIM_HAVE_FASTDDS
  fastdds::clean_shared_memory();
#endif
}

}  // namespace mechsim::transport
