// The QoS contract of participant.h for Cyclone DDS, in one place: the typed endpoints
// (cyclone_participant.cpp) and the raw ones of the tools (cyclone_raw.cpp) must match.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "dds/dds.h"
#include "mechsim/transport/security.h"

namespace mechsim::transport::cyclone {

// RAII for dds_qos_t.
struct Qos {
  dds_qos_t* q = dds_create_qos();
  Qos() = default;
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  ~Qos() { dds_delete_qos(q); }
};

enum class QosKind { data, redundant, control, status, agent };

// data: RELIABLE, KEEP_ALL, VOLATILE; control: RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1;
// redundant: BEST_EFFORT, KEEP_LAST 64; status: BEST_EFFORT, KEEP_LAST 256; agent: RELIABLE, KEEP_ALL, VOLATILE.
inline void set_qos(Qos& qos, QosKind kind) {
  switch (kind) {
    case QosKind::data:
      dds_qset_reliability(qos.q, DDS_RELIABILITY_RELIABLE, DDS_SECS(30));
      dds_qset_history(qos.q, DDS_HISTORY_KEEP_ALL, 0);
      dds_qset_durability(qos.q, DDS_DURABILITY_VOLATILE);
      break;
    case QosKind::redundant:  // the best-effort twin of a data topic
      dds_qset_reliability(qos.q, DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_history(qos.q, DDS_HISTORY_KEEP_LAST, 64);
      dds_qset_durability(qos.q, DDS_DURABILITY_VOLATILE);
      break;
    case QosKind::control:
      dds_qset_reliability(qos.q, DDS_RELIABILITY_RELIABLE, DDS_SECS(10));
      dds_qset_history(qos.q, DDS_HISTORY_KEEP_LAST, 1);
      dds_qset_durability(qos.q, DDS_DURABILITY_TRANSIENT_LOCAL);
      break;
    case QosKind::agent:  // requests and replies of the agent conversation
      dds_qset_reliability(qos.q, DDS_RELIABILITY_RELIABLE, DDS_SECS(10));
      dds_qset_history(qos.q, DDS_HISTORY_KEEP_ALL, 0);
      dds_qset_durability(qos.q, DDS_DURABILITY_VOLATILE);
      break;
    case QosKind::status:
      dds_qset_reliability(qos.q, DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_history(qos.q, DDS_HISTORY_KEEP_LAST, 256);
      break;
  }
}

// A participant on `domain_id`, secured with `security`'s identity when given (the
// properties of security.h on its QoS; docs/security.md). Throws std::runtime_error.
inline dds_entity_t create_participant_entity(int domain_id, const std::optional<SecurityIdentity>& security) {
  Qos qos;
  if (security)
    for (const auto& [name, value] : security_properties(*security, "cyclone")) dds_qset_prop(qos.q, name.c_str(), value.c_str());
  const dds_entity_t pp = dds_create_participant(static_cast<dds_domainid_t>(domain_id), qos.q, nullptr);
  if (pp < 0)
    throw std::runtime_error("Cyclone DDS: create participant on domain " + std::to_string(domain_id) +
                             (security ? " with DDS security identity '" + security->name + "' of " + security->dir +
                                             " (the plugins' reason is in the Cyclone DDS log, enable it with "
                                             "CYCLONEDDS_URI <Tracing>)"
                                       : std::string()) +
                             ": " + dds_strretcode(pp));
  return pp;
}

}  // namespace mechsim::transport::cyclone
