// The QoS contract of participant.h for Cyclone DDS, in one place: the typed endpoints
// (cyclone_participant.cpp) and the raw ones of the tools (cyclone_raw.cpp) must match.
#pragma once

#include "dds/dds.h"

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

}  // namespace mechsim::transport::cyclone
