// Cyclone DDS (C API) backend of the raw-CDR seam (raw.h).
//
// Reading: dds_takecdr hands out the received serdata; ddsi_serdata_size/_to_ser give its
// serialised form with the encapsulation header, i.e. the bytes the writer sent.
// Writing: Cyclone 0.10 offers no public way to get a topic's sertype (which
// dds_writecdr needs), so a raw sample is validated and brought to native byte order with
// dds_stream_normalize_data, deserialised into the generated struct with dds_stream_read
// (the type's own marshalling ops) and written with dds_write. For mechsim's @final types
// Cyclone serialises that struct back to the same bytes (checked by the recorder's unit
// tests: take raw -> write raw -> take raw gives identical bytes).
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "control.h"
#include "cyclone_qos.h"
#include "cyclone_types.h"
#include "fmu.h"
#include "dds/dds.h"
#include "dds/ddsi/ddsi_cdrstream.h"
#include "dds/ddsi/ddsi_serdata.h"
#include "mechsim/transport/raw.h"
#include "status.h"

namespace mechsim::transport {

namespace {

constexpr const char* kControlType = "mechsim::msg::Control";
constexpr const char* kStatusType = "mechsim::msg::Status";

// The generated descriptor of a known type (scoped name), or nullptr.
const dds_topic_descriptor_t* descriptor_of(std::string_view scoped) {
  if (scoped == kControlType) return &mechsim_msg_Control_desc;
  if (scoped == kStatusType) return &mechsim_msg_Status_desc;
  if (scoped == kFmuOutputsTypeName) return &mechsim_msg_FmuOutputs_desc;
  if (const TopicType* t = find_topic_type(scoped); t && t->idl_name == scoped)
    return cyclone::cyclone_type(*t).descriptor;
  return nullptr;
}

}  // namespace

namespace cyclone {
namespace {

[[noreturn]] void fail(const std::string& what, dds_return_t rc) {
  throw std::runtime_error("Cyclone DDS: " + what + ": " + dds_strretcode(rc));
}

dds_entity_t check(dds_entity_t e, const std::string& what) {
  if (e < 0) fail(what, e);
  return e;
}

// The same QoS as the typed endpoints (cyclone_qos.h): a raw endpoint must match them.
QosKind qos_kind(TopicKind kind) {
  switch (kind) {
    case TopicKind::control: return QosKind::control;
    case TopicKind::status: return QosKind::status;
    case TopicKind::data: break;
  }
  return QosKind::data;
}

// Encapsulation identifiers (DDS-XTYPES 1.3, 7.6.3.1.2), as the first two bytes read
// big-endian. Only the plain representations can carry a @final type.
struct Encapsulation {
  bool big_endian = false;
  std::uint32_t xcdr_version = 1;
};

std::optional<Encapsulation> plain_encapsulation(std::span<const std::byte> cdr) {
  if (cdr.size() < 4) return std::nullopt;
  const unsigned id = (std::to_integer<unsigned>(cdr[0]) << 8) | std::to_integer<unsigned>(cdr[1]);
  switch (id) {
    case 0x0000: return Encapsulation{true, 1};   // CDR_BE
    case 0x0001: return Encapsulation{false, 1};  // CDR_LE
    case 0x0006: return Encapsulation{true, 2};   // CDR2_BE
    case 0x0007: return Encapsulation{false, 2};  // CDR2_LE
    default: return std::nullopt;
  }
}

template <class T>
T load(std::span<const std::byte> cdr, std::size_t offset, bool big_endian) {
  std::array<std::byte, sizeof(T)> b;
  std::memcpy(b.data(), cdr.data() + offset, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b.begin(), b.end());
  T v;
  std::memcpy(&v, b.data(), sizeof(T));
  return v;
}

// The header every mechsim type starts with: three 8-byte members at payload offsets 0, 8
// and 16, which are aligned under XCDR1 (8) and XCDR2 (4) alike.
SampleHeader decode_header(std::span<const std::byte> cdr) {
  SampleHeader h;
  auto enc = plain_encapsulation(cdr);
  if (!enc || cdr.size() < 4 + 24) return h;
  h.run_id = load<std::uint64_t>(cdr, 4, enc->big_endian);
  h.step = load<std::uint64_t>(cdr, 12, enc->big_endian);
  h.t = load<double>(cdr, 20, enc->big_endian);
  return h;
}

class CycloneRawReader final : public RawReader {
 public:
  CycloneRawReader(dds_entity_t reader, std::string topic, std::string type)
      : reader_(reader), topic_(std::move(topic)), type_(std::move(type)) {}
  ~CycloneRawReader() override {
    for (std::size_t i = next_; i < count_; ++i) ddsi_serdata_unref(batch_[i]);
    dds_delete(reader_);
  }
  bool take(RawSample& sample) override {
    for (;;) {
      if (next_ == count_ && !refill()) return false;
      ddsi_serdata* d = batch_[next_];
      const bool valid = infos_[next_].valid_data;
      const std::int64_t stamp = infos_[next_].source_timestamp;
      ++next_;
      if (valid) {
        const std::uint32_t size = ddsi_serdata_size(d);
        sample.cdr.resize(size);
        ddsi_serdata_to_ser(d, 0, size, sample.cdr.data());
        sample.header = decode_header(sample.cdr);
        sample.source_timestamp_ns = stamp;
      }
      ddsi_serdata_unref(d);
      if (valid) return true;
    }
  }
  int matched_writers() const override {
    dds_subscription_matched_status_t st{};
    return dds_get_subscription_matched_status(reader_, &st) == DDS_RETCODE_OK ? static_cast<int>(st.current_count) : 0;
  }
  std::uint64_t lost_samples() const override {
    dds_sample_lost_status_t st{};
    if (dds_get_sample_lost_status(reader_, &st) == DDS_RETCODE_OK) lost_ += st.total_count_change;
    return lost_;
  }
  const std::string& topic() const override { return topic_; }
  const std::string& type_name() const override { return type_; }

 private:
  bool refill() {
    next_ = count_ = 0;
    dds_return_t n = dds_takecdr(reader_, batch_.data(), static_cast<uint32_t>(batch_.size()), infos_.data(), DDS_ANY_STATE);
    if (n < 0) fail("take (raw) on " + topic_, n);
    count_ = static_cast<std::size_t>(n);
    return count_ > 0;
  }
  dds_entity_t reader_;
  std::string topic_, type_;
  // Taken in batches: one dds_takecdr call per 64 samples instead of one per sample.
  std::array<ddsi_serdata*, 64> batch_{};
  std::array<dds_sample_info_t, 64> infos_{};
  std::size_t next_ = 0, count_ = 0;
  mutable std::uint64_t lost_ = 0;  // the status's total_count is 32 bits; sum the changes
};

class CycloneRawWriter final : public RawWriter {
 public:
  CycloneRawWriter(dds_entity_t writer, const dds_topic_descriptor_t* desc, std::string topic)
      : writer_(writer), desc_(desc), topic_(std::move(topic)) {}
  ~CycloneRawWriter() override { dds_delete(writer_); }
  void write(std::span<const std::byte> cdr) override {
    auto enc = plain_encapsulation(cdr);
    if (!enc) throw std::invalid_argument("raw write on " + topic_ + ": not a plain CDR encapsulation");
    // A writable, 8-byte aligned copy of the payload: normalisation works in place.
    const std::size_t size = cdr.size() - 4;
    payload_.assign((size + 7) / 8, 0);
    std::memcpy(payload_.data(), cdr.data() + 4, size);
    char* data = reinterpret_cast<char*>(payload_.data());
    std::uint32_t actual = 0;
    const bool swap = enc->big_endian != (std::endian::native == std::endian::big);
    if (!dds_stream_normalize_data(data, &actual, static_cast<std::uint32_t>(size), swap, enc->xcdr_version,
                                   desc_->m_ops))
      throw std::invalid_argument("raw write on " + topic_ + ": the bytes are not a valid " + desc_->m_typename);
    sample_.assign((desc_->m_size + 7) / 8, 0);
    dds_istream_t is;
    dds_istream_init(&is, actual, data, enc->xcdr_version);
    dds_stream_read(&is, reinterpret_cast<char*>(sample_.data()), desc_->m_ops);
    dds_istream_fini(&is);
    const dds_return_t rc = dds_write(writer_, sample_.data());
    dds_stream_free_sample(sample_.data(), desc_->m_ops);  // strings the read allocated (none for bounded ones)
    if (rc != DDS_RETCODE_OK) fail("write (raw) on " + topic_, rc);
  }
  int matched_readers() const override {
    dds_publication_matched_status_t st{};
    return dds_get_publication_matched_status(writer_, &st) == DDS_RETCODE_OK ? static_cast<int>(st.current_count) : 0;
  }
  void flush(std::chrono::nanoseconds timeout) override { dds_wait_for_acks(writer_, timeout.count()); }

 private:
  dds_entity_t writer_;
  const dds_topic_descriptor_t* desc_;
  std::string topic_;
  std::vector<std::uint64_t> payload_, sample_;
};

class CycloneRawParticipant final : public RawParticipant {
 public:
  CycloneRawParticipant(int domain_id, const std::optional<SecurityIdentity>& security) {
    participant_ = create_participant_entity(domain_id, security);
    check(dds_get_guid(participant_, &own_guid_), "get participant guid");
    waitset_ = check(dds_create_waitset(participant_), "create waitset");
    guard_ = check(dds_create_guardcondition(participant_), "create guard condition");
    check(dds_waitset_attach(waitset_, guard_, guard_), "attach guard condition");
    for (dds_entity_t builtin : {DDS_BUILTIN_TOPIC_DCPSPUBLICATION, DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION}) {
      dds_entity_t r = check(dds_create_reader(participant_, builtin, nullptr, nullptr), "create discovery reader");
      // Wakes wait() when an endpoint appears or goes; poll_discovery() takes the samples.
      dds_entity_t cond = check(dds_create_readcondition(r, DDS_ANY_STATE), "create discovery condition");
      check(dds_waitset_attach(waitset_, cond, r), "attach discovery condition");
      discovery_readers_.push_back(r);
    }
  }
  ~CycloneRawParticipant() override { dds_delete(participant_); }

  std::unique_ptr<RawReader> create_reader(const std::string& topic_name, const std::string& type_name) override {
    std::string scoped;
    const dds_entity_t t = topic(topic_name, type_name, scoped);
    Qos qos;
    set_qos(qos, qos_kind(topic_kind(topic_name)));
    dds_qset_userdata(qos.q, kToolReaderUserData, std::strlen(kToolReaderUserData));
    dds_entity_t r = check(dds_create_reader(participant_, t, qos.q, nullptr),
                           "create raw reader on " + topic_name);
    dds_entity_t cond = check(dds_create_readcondition(r, DDS_ANY_STATE), "create read condition");
    check(dds_waitset_attach(waitset_, cond, r), "attach read condition");
    return std::make_unique<CycloneRawReader>(r, topic_name, scoped);
  }

  std::unique_ptr<RawWriter> create_writer(const std::string& topic_name, const std::string& type_name) override {
    std::string scoped;
    const dds_entity_t t = topic(topic_name, type_name, scoped);
    Qos qos;
    set_qos(qos, qos_kind(topic_kind(topic_name)));
    dds_entity_t w = check(dds_create_writer(participant_, t, qos.q, nullptr),
                           "create raw writer on " + topic_name);
    return std::make_unique<CycloneRawWriter>(w, descriptor_of(scoped), topic_name);
  }

  std::vector<DiscoveredTopic> discovered_topics() override {
    std::lock_guard lock(discovery_mutex_);
    poll_discovery();
    std::map<std::pair<std::string, std::string>, DiscoveredTopic> topics;
    for (const auto& [key, e] : endpoints_) {
      if (e.own) continue;
      auto& t = topics[{e.topic, e.type}];
      t.name = e.topic;
      t.type_name = e.type;
      ++(key.first == 0 ? t.publishers : t.subscribers);
    }
    std::vector<DiscoveredTopic> out;
    for (auto& [key, t] : topics) out.push_back(std::move(t));
    return out;
  }

  bool wait(std::chrono::nanoseconds timeout) override {
    std::array<dds_attach_t, 64> triggered{};
    dds_return_t n = dds_waitset_wait(waitset_, triggered.data(), triggered.size(), timeout.count());
    if (n < 0) fail("waitset wait", n);
    for (dds_return_t i = 0; i < std::min<dds_return_t>(n, static_cast<dds_return_t>(triggered.size())); ++i) {
      if (triggered[i] == static_cast<dds_attach_t>(guard_)) {
        bool was = false;
        dds_take_guardcondition(guard_, &was);
      }
      for (dds_entity_t r : discovery_readers_)
        if (triggered[i] == static_cast<dds_attach_t>(r)) {
          std::lock_guard lock(discovery_mutex_);
          if (poll_discovery()) ++discovery_events_;
        }
    }
    return n > 0;
  }

  void wake() override { dds_set_guardcondition(guard_, true); }
  std::uint64_t discovery_events() const override { return discovery_events_; }

 private:
  struct Endpoint {
    std::string topic, type;
    bool own = false;  // of this participant
  };

  // Takes what the discovery readers learned since the last call into endpoints_: a live
  // endpoint is added (keyed by its instance), a gone one (disposed or unregistered)
  // removed. One sample per take: loaned reads of 64 and of 1024 built-in samples from
  // the same reader crashed Cyclone 0.10.2 here (heap corruption in its loan handling).
  bool poll_discovery() {
    bool changed = false;
    for (std::size_t k = 0; k < discovery_readers_.size(); ++k) {
      for (;;) {
        void* buf[1] = {nullptr};
        dds_sample_info_t info;
        const dds_return_t n = dds_take(discovery_readers_[k], buf, &info, 1, 1);
        if (n < 0) fail("take discovery data", n);
        if (n == 0) break;
        const auto key = std::make_pair(static_cast<int>(k), info.instance_handle);
        if (info.valid_data && info.instance_state == DDS_IST_ALIVE) {
          const auto* e = static_cast<const dds_builtintopic_endpoint_t*>(buf[0]);
          endpoints_[key] = {e->topic_name ? e->topic_name : "", e->type_name ? e->type_name : "",
                             std::memcmp(&e->participant_key, &own_guid_, sizeof own_guid_) == 0};
        } else if (info.instance_state != DDS_IST_ALIVE) {
          endpoints_.erase(key);
        }
        dds_return_loan(discovery_readers_[k], buf, n);
        changed = true;
      }
    }
    return changed;
  }

  // The topic entity for (name, type); throws std::invalid_argument for an unknown type or
  // a name already used here with another type.
  dds_entity_t topic(const std::string& name, const std::string& type_name, std::string& scoped) {
    scoped = scoped_type_name(type_name);
    const dds_topic_descriptor_t* desc = descriptor_of(scoped);
    if (!desc) throw std::invalid_argument("topic " + name + ": the raw seam knows no type '" + type_name + "'");
    auto it = topics_.find(name);
    if (it != topics_.end()) {
      if (it->second.second != scoped)
        throw std::invalid_argument("topic " + name + " is already used with type " + it->second.second);
      return it->second.first;
    }
    dds_entity_t t = check(dds_create_topic(participant_, desc, name.c_str(), nullptr, nullptr), "create topic " + name);
    topics_.emplace(name, std::make_pair(t, scoped));
    return t;
  }

  dds_entity_t participant_ = 0;
  dds_guid_t own_guid_{};
  dds_entity_t waitset_ = 0;
  dds_entity_t guard_ = 0;
  std::vector<dds_entity_t> discovery_readers_;  // DCPSPublication, DCPSSubscription
  std::mutex discovery_mutex_;
  std::map<std::pair<int, dds_instance_handle_t>, Endpoint> endpoints_;  // (0 writer / 1 reader, instance)
  std::atomic<std::uint64_t> discovery_events_{0};
  std::map<std::string, std::pair<dds_entity_t, std::string>> topics_;  // name -> (topic, scoped type)
};

}  // namespace
}  // namespace cyclone

namespace cyclone {
std::unique_ptr<RawParticipant> create_cyclone_raw_participant(int domain_id, const std::optional<SecurityIdentity>& security) {
  return std::make_unique<CycloneRawParticipant>(domain_id, security);
}
}  // namespace cyclone

}  // namespace mechsim::transport
