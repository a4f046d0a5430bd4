// The raw-CDR side of the transport seam, for tools that handle samples without knowing
// their fields: the recorder (samples exactly as serialised on the wire), the player
// (publishes such bytes again), and the inspection commands (what is on a domain).
//
// A raw sample is the serialised sample with its 4-byte encapsulation header (CDR
// representation identifier + options, e.g. 00 01 00 00 for XCDR1 little endian), as the
// writer put it on the wire. The seam also decodes the fixed header every mechsim sample
// starts with ({run_id, step, t}, see idl/header.idl), since that is at the same place in
// every type.
//
// Topics are named by topic name and IDL type name ("mechsim::msg::CamState", or the
// short "CamState"); the QoS follows the topic kind exactly as the typed seam does
// (participant.h): data RELIABLE + KEEP_ALL, control RELIABLE + TRANSIENT_LOCAL + KEEP_LAST
// 1, status BEST_EFFORT + KEEP_LAST. A KEEP_ALL reliable raw reader that falls behind
// slows the writers down (back-pressure) rather than losing samples.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mechsim/transport/messages.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::transport {

enum class TopicKind { data, control, status };

// mechsim/control and mechsim/status by name; every other topic is a data topic.
TopicKind topic_kind(std::string_view topic);

// The IDL types the raw seam can read and write: every data type of topic_types.h plus
// mechsim::msg::Control and mechsim::msg::Status. Fully scoped names.
std::vector<std::string> raw_type_names();
// The fully scoped name of a known type given its scoped or short name; "" if unknown.
std::string scoped_type_name(std::string_view short_or_scoped_name);

struct RawSample {
  std::vector<std::byte> cdr;          // encapsulation header + payload, as on the wire
  SampleHeader header;                 // decoded from the payload
  std::int64_t source_timestamp_ns = 0;  // the writer's clock at write [ns since the Unix epoch]
};

class RawReader {
 public:
  virtual ~RawReader() = default;
  // Takes the next valid sample if there is one (disposal notices are skipped). The
  // sample's buffer is reused: pass the same RawSample to avoid an allocation per sample.
  virtual bool take(RawSample& sample) = 0;
  virtual int matched_writers() const = 0;
  // Samples DDS reports lost on the way to this reader (SAMPLE_LOST status, cumulative):
  // only a best-effort topic can lose any.
  virtual std::uint64_t lost_samples() const = 0;
  virtual const std::string& topic() const = 0;
  virtual const std::string& type_name() const = 0;  // fully scoped
};

class RawWriter {
 public:
  virtual ~RawWriter() = default;
  // Publishes one serialised sample (encapsulation header included). Throws
  // std::invalid_argument when the bytes are not a valid sample of the writer's type.
  virtual void write(std::span<const std::byte> cdr) = 0;
  virtual int matched_readers() const = 0;
  // Waits until every matched reader acknowledged what was written (before a player exits).
  virtual void flush(std::chrono::nanoseconds timeout) = 0;
};

// What the built-in discovery topics (DCPSPublication, DCPSSubscription) say about one
// topic on the domain: endpoints of this participant itself are not counted.
struct DiscoveredTopic {
  std::string name;
  std::string type_name;  // as announced; a topic announced with two types appears twice
  int publishers = 0;     // writers
  int subscribers = 0;    // readers
};

class RawParticipant {
 public:
  virtual ~RawParticipant() = default;
  // Throws std::invalid_argument for a type the seam does not know (raw_type_names()),
  // std::runtime_error when DDS refuses.
  virtual std::unique_ptr<RawReader> create_reader(const std::string& topic, const std::string& type_name) = 0;
  virtual std::unique_ptr<RawWriter> create_writer(const std::string& topic, const std::string& type_name) = 0;
  // Live endpoints of other participants on the domain, grouped by (topic, type), sorted.
  virtual std::vector<DiscoveredTopic> discovered_topics() = 0;
  // How many times wait() woke up because endpoints appeared or went: a caller that
  // follows discovery calls discovered_topics() only when this changed.
  virtual std::uint64_t discovery_events() const = 0;
  // Blocks until a reader of this participant may have data, a new endpoint was
  // discovered, wake() was called, or the timeout passed. Returns false on timeout.
  // Spurious wake-ups are allowed.
  virtual bool wait(std::chrono::nanoseconds timeout) = 0;
  // Interrupts wait() (safe from any thread).
  virtual void wake() = 0;
};

// Every raw reader carries this USER_DATA QoS value, so that a node can tell a tool's
// reader (recorder, `topic echo`/`hz`) from a partner's when it counts the readers matched
// with its writer: a tool's reader must not stand in for a partner that is not matched yet.
inline constexpr const char* kToolReaderUserData = "mechsim:tool";

// A participant of its own on `domain_id` (the network configuration comes from
// CYCLONEDDS_URI, as for the typed seam). Throws std::runtime_error when the vendor is not
// compiled in or the participant cannot be created. Only "cyclone" has a raw backend.
// Secured like create_participant() when MECHSIM_DDS_SECURITY / MECHSIM_DDS_IDENTITY are set
// (security.h, docs/security.md).
std::unique_ptr<RawParticipant> create_raw_participant(const std::string& vendor, int domain_id);

}  // namespace mechsim::transport
