// The vendor-neutral part of the raw-CDR seam (raw.h): topic kinds, the known type names,
// and the factory that picks a vendor's raw backend. Builds without any DDS vendor, so the
// tools that use the seam link in every build configuration.
#include "mechsim/transport/raw.h"
#include "mechsim/transport/security.h"

#include <stdexcept>

#ifdef MECHSIM_HAVE_CYCLONEDDS
namespace mechsim::transport::cyclone {
std::unique_ptr<RawParticipant> create_cyclone_raw_participant(int domain_id, const std::optional<SecurityIdentity>& security);  // cyclone_raw.cpp
}
#endif

namespace mechsim::transport {

TopicKind topic_kind(std::string_view topic) {
  if (topic == kControlTopic) return TopicKind::control;
  if (topic == kStatusTopic) return TopicKind::status;
  return TopicKind::data;
}

std::vector<std::string> raw_type_names() {
  std::vector<std::string> names;
  for (const TopicType* t : all_topic_types()) names.push_back(t->idl_name);
  names.push_back(kFmuOutputsTypeName);  // every FMU participant's topic type (idl/fmu.idl)
  names.push_back("mechsim::msg::Control");
  names.push_back("mechsim::msg::Status");
  return names;
}

std::string scoped_type_name(std::string_view name) {
  for (const std::string& scoped : raw_type_names()) {
    std::string_view s = scoped;
    if (name == s || name == s.substr(s.rfind(':') + 1)) return scoped;
  }
  return "";
}

std::unique_ptr<RawParticipant> create_raw_participant(const std::string& vendor, int domain_id) {
#ifdef MECHSIM_HAVE_CYCLONEDDS
  if (vendor == "cyclone") return cyclone::create_cyclone_raw_participant(domain_id, security_from_environment());
#endif
  // Only Cyclone has a raw backend: the tools (recorder, player, topic inspection) are
  // Cyclone participants that interoperate with nodes of either vendor on the wire.
  throw std::runtime_error("no raw-CDR backend for DDS vendor '" + vendor + "'" +
#ifdef MECHSIM_HAVE_CYCLONEDDS
                           std::string(" (only 'cyclone' has one)")
#else
                           std::string(": this build has no Cyclone DDS (MECHSIM_WITH_CYCLONEDDS=OFF), "
                                       "so recording and topic inspection are not available")
#endif
  );
}

}  // namespace mechsim::transport
