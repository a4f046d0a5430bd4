// Fast DDS 2.9 (C++ DDS API) backend of the transport seam. Same QoS contract as the
// Cyclone backend (participant.h, docs/dds.md), so the two interoperate topic by topic.
#include "fastdds_participant.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include <fastdds/dds/core/condition/GuardCondition.hpp>
#include <fastdds/dds/core/condition/WaitSet.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/ReadCondition.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "fastdds_types.h"
#include "mechsim/transport/security.h"
#include "mechsim/transport/raw.h"
#include "fastddsgen/agentPubSubTypes.h"
#include "fastddsgen/controlPubSubTypes.h"
#include "fastddsgen/statusPubSubTypes.h"

namespace mechsim::transport::fastdds {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;
using ReturnCode = eprosima::fastrtps::types::ReturnCode_t;

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("Fast DDS: " + what); }

template <class T>
T* check(T* entity, const std::string& what) {
  if (entity == nullptr) fail(what + " failed (see the Fast DDS log above)");
  return entity;
}

Duration_t to_duration(std::chrono::nanoseconds d) {
  if (d.count() < 0) d = std::chrono::nanoseconds(0);
  const auto s = std::chrono::duration_cast<std::chrono::seconds>(d);
  if (s.count() >= std::numeric_limits<std::int32_t>::max()) return eprosima::fastrtps::c_TimeInfinite;
  return Duration_t(static_cast<std::int32_t>(s.count()), static_cast<std::uint32_t>((d - s).count()));
}

// QoS contract (participant.h). Everything else (data sharing, memory policy) comes from
// the default profiles of the XML file, which switch data sharing off (docs/dds.md).
void data_qos(dds::ReliabilityQosPolicy& reliability, dds::HistoryQosPolicy& history, dds::DurabilityQosPolicy& durability) {
  reliability.kind = dds::RELIABLE_RELIABILITY_QOS;
  reliability.max_blocking_time = Duration_t(30, 0);
  history.kind = dds::KEEP_ALL_HISTORY_QOS;
  durability.kind = dds::VOLATILE_DURABILITY_QOS;
}

void redundant_qos(dds::ReliabilityQosPolicy& reliability, dds::HistoryQosPolicy& history, dds::DurabilityQosPolicy& durability) {
  reliability.kind = dds::BEST_EFFORT_RELIABILITY_QOS;
  history.kind = dds::KEEP_LAST_HISTORY_QOS;
  history.depth = 64;
  durability.kind = dds::VOLATILE_DURABILITY_QOS;
}

void control_qos(dds::ReliabilityQosPolicy& reliability, dds::HistoryQosPolicy& history, dds::DurabilityQosPolicy& durability) {
  reliability.kind = dds::RELIABLE_RELIABILITY_QOS;
  reliability.max_blocking_time = Duration_t(10, 0);
  history.kind = dds::KEEP_LAST_HISTORY_QOS;
  history.depth = 1;
  durability.kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
}

void status_qos(dds::ReliabilityQosPolicy& reliability, dds::HistoryQosPolicy& history, dds::DurabilityQosPolicy& durability) {
  reliability.kind = dds::BEST_EFFORT_RELIABILITY_QOS;
  history.kind = dds::KEEP_LAST_HISTORY_QOS;
  history.depth = 256;
  durability.kind = dds::VOLATILE_DURABILITY_QOS;
}

void agent_qos(dds::ReliabilityQosPolicy& reliability, dds::HistoryQosPolicy& history, dds::DurabilityQosPolicy& durability) {
  reliability.kind = dds::RELIABLE_RELIABILITY_QOS;
  reliability.max_blocking_time = Duration_t(10, 0);
  history.kind = dds::KEEP_ALL_HISTORY_QOS;
  durability.kind = dds::VOLATILE_DURABILITY_QOS;
}

using QosSetter = void (*)(dds::ReliabilityQosPolicy&, dds::HistoryQosPolicy&, dds::DurabilityQosPolicy&);

void copy_bounded(std::string& dst, const std::string& src, std::size_t capacity) { dst = src.substr(0, capacity); }

}  // namespace

// The DDS entities of one participant. Writers and readers hold a shared_ptr to it, so the
// participant is deleted only after the last of them (Fast DDS refuses to delete a
// participant that still has entities, and a dangling DataWriter* would crash).
// The readers of mechsim's tools (recorder, `topic echo`), known by their USER_DATA
// (kToolReaderUserData, raw.h), per topic: a node's writer must not count them as the
// partner it waits for. Fast DDS 2.9 cannot say which readers a writer is matched with
// (get_matched_subscription_data is unsupported), so matched_readers() subtracts the tool
// readers discovered on the topic. A tool reader discovered but not matched yet makes the
// count low for a moment: readiness then waits a little longer, never starts too early.
class ToolReaderTracker final : public dds::DomainParticipantListener {
 public:
  void on_subscriber_discovery(dds::DomainParticipant*, eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override {
    using Status = eprosima::fastrtps::rtps::ReaderDiscoveryInfo::DISCOVERY_STATUS;
    const auto& data = info.info.m_qos.m_userData.data_vec();
    const std::string tag = kToolReaderUserData;
    const bool tool = data.size() == tag.size() && std::equal(data.begin(), data.end(), tag.begin(),
                                                              [](auto a, char b) { return static_cast<char>(a) == b; });
    std::lock_guard lock(mutex_);
    if (info.status == Status::REMOVED_READER || !tool)
      readers_.erase(info.info.guid());
    else
      readers_[info.info.guid()] = info.info.topicName().c_str();
  }
  int on_topic(const std::string& topic) const {
    std::lock_guard lock(mutex_);
    return static_cast<int>(std::count_if(readers_.begin(), readers_.end(), [&](const auto& r) { return r.second == topic; }));
  }

 private:
  mutable std::mutex mutex_;
  std::map<eprosima::fastrtps::rtps::GUID_t, std::string> readers_;
};

// The DDS entities of one DomainParticipant: one per FastParticipant, or one for every
// member of a process group (create_group_member_participant, backends.h), each member then
// keeping its own waitset (FastCore).
struct FastDomainParticipant {
  ToolReaderTracker tool_readers;  // the participant's listener: outlives the participant
  dds::DomainParticipant* participant = nullptr;
  dds::Publisher* publisher = nullptr;
  dds::Subscriber* subscriber = nullptr;

  FastDomainParticipant(int domain_id, const std::optional<SecurityIdentity>& security);
  FastDomainParticipant(const FastDomainParticipant&) = delete;
  FastDomainParticipant& operator=(const FastDomainParticipant&) = delete;

  ~FastDomainParticipant() {
    if (participant == nullptr) return;
    participant->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant);
  }

  dds::Topic* topic(const std::string& name, dds::TopicDataType* type_support) {
    dds::TypeSupport type(type_support);  // owns type_support from here on
    std::lock_guard lock(topics_mutex_);  // the members of a group create theirs at once
    auto it = topics_.find(name);
    if (it != topics_.end()) return it->second;
    if (participant->find_type(type.get_type_name()).empty() && participant->register_type(type) != ReturnCode::RETCODE_OK)
      fail("register type " + type.get_type_name());
    dds::Topic* t = check(participant->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT), "create topic " + name);
    topics_.emplace(name, t);
    return t;
  }

  dds::DataWriter* writer(const std::string& topic_name, dds::TopicDataType* type_support, QosSetter qos_setter) {
    dds::Topic* t = topic(topic_name, type_support);
    dds::DataWriterQos qos = publisher->get_default_datawriter_qos();
    qos_setter(qos.reliability(), qos.history(), qos.durability());
    // A KEEP_ALL writer frees its history only on acknowledgements, and a reader that
    // already holds everything answers only a non-final heartbeat: the periodic one, every
    // 3 s by default. With the default limit of 400 unacknowledged samples a lock-step
    // writer then stalls for up to 3 s every 400 steps (measured over UDP, and with Cyclone
    // readers). A 10 ms period keeps the history short; it costs nothing once all is acked.
    //
    // Lost samples (docs/faults.md): in lock-step nothing follows a lost sample until it is
    // repaired, so the repair waits for the writer's next heartbeat, the reader's NACK and
    // the writer's answer. A 5 ms period and no deliberate delays on either side (default
    // 5 ms each) make a repair cost ~5 ms instead of ~15 ms. Not 1 ms: a lock-step sample
    // stays unacknowledged until the next heartbeat, so every writer heartbeats (and its
    // reader answers) once per period of wall time for as long as the run lasts; when many
    // participants share the cores a step takes longer and this traffic per step grows
    // with the participants (docs/performance.md).
    qos.reliable_writer_qos().times.heartbeatPeriod = Duration_t(0, 5'000'000);
    qos.reliable_writer_qos().times.nackResponseDelay = Duration_t(0, 0);
    return check(publisher->create_datawriter(t, qos), "create writer on " + topic_name);
  }

  dds::DataReader* reader(const std::string& topic_name, dds::TopicDataType* type_support, QosSetter qos_setter) {
    dds::Topic* t = topic(topic_name, type_support);
    dds::DataReaderQos qos = subscriber->get_default_datareader_qos();
    qos_setter(qos.reliability(), qos.history(), qos.durability());
    qos.reliable_reader_qos().times.heartbeatResponseDelay = Duration_t(0, 0);  // NACK at once (see writer())
    return check(subscriber->create_datareader(t, qos), "create reader on " + topic_name);
  }

 private:
  std::mutex topics_mutex_;
  std::map<std::string, dds::Topic*> topics_;
};

// What one FastParticipant owns: its DomainParticipant (perhaps shared) and one waitset for
// wait(): a read condition per reader (triggered while the reader holds a sample, as
// Cyclone's) and a guard condition for wake().
struct FastCore {
  std::shared_ptr<FastDomainParticipant> domain;
  dds::GuardCondition guard;
  dds::WaitSet waitset;

  explicit FastCore(std::shared_ptr<FastDomainParticipant> domain_participant) : domain(std::move(domain_participant)) {
    waitset.attach_condition(guard);
  }

  dds::DataWriter* writer(const std::string& topic_name, dds::TopicDataType* type_support, QosSetter qos_setter) {
    return domain->writer(topic_name, type_support, qos_setter);
  }
  dds::DataReader* reader(const std::string& topic_name, dds::TopicDataType* type_support, QosSetter qos_setter) {
    return domain->reader(topic_name, type_support, qos_setter);
  }
  void delete_writer(dds::DataWriter* writer) { domain->publisher->delete_datawriter(writer); }

  dds::ReadCondition* attach(dds::DataReader* reader) {
    dds::ReadCondition* c = check(
        reader->create_readcondition(dds::ANY_SAMPLE_STATE, dds::ANY_VIEW_STATE, dds::ANY_INSTANCE_STATE),
        "create read condition on " + reader->get_topicdescription()->get_name());
    waitset.attach_condition(*c);
    return c;
  }

  void delete_reader(dds::DataReader* reader, dds::ReadCondition* condition) {
    waitset.detach_condition(*condition);
    reader->delete_readcondition(condition);
    domain->subscriber->delete_datareader(reader);
  }
};

namespace {

int publication_matched(dds::DataWriter* w) {
  dds::PublicationMatchedStatus st;
  return w->get_publication_matched_status(st) == ReturnCode::RETCODE_OK ? st.current_count : 0;
}

int subscription_matched(dds::DataReader* r) {
  dds::SubscriptionMatchedStatus st;
  return r->get_subscription_matched_status(st) == ReturnCode::RETCODE_OK ? st.current_count : 0;
}

// Takes one valid sample into `data` (a generated object); skips disposal/unregistration
// notices. Returns false when none is left.
bool take_one(dds::DataReader* reader, void* data, dds::SampleInfo* info_out = nullptr) {
  dds::SampleInfo local;
  dds::SampleInfo& info = info_out != nullptr ? *info_out : local;
  for (;;) {
    ReturnCode rc = reader->take_next_sample(data, &info);
    if (rc == ReturnCode::RETCODE_NO_DATA) return false;
    if (rc != ReturnCode::RETCODE_OK) fail("take on " + reader->get_topicdescription()->get_name());
    if (info.valid_data) return true;
  }
}

std::string guid_text(const eprosima::fastrtps::rtps::GUID_t& g) {
  unsigned char bytes[16];
  std::memcpy(bytes, g.guidPrefix.value, 12);
  std::memcpy(bytes + 12, g.entityId.value, 4);
  return mechsim::transport::guid_text(bytes);
}

// Base of every writer/reader: keeps the core alive and deletes its entity.
class Endpoint {
 protected:
  explicit Endpoint(std::shared_ptr<FastCore> core) : core_(std::move(core)) {}
  std::shared_ptr<FastCore> core_;
};

class FastSampleWriter final : public SampleWriter, Endpoint {
 public:
  FastSampleWriter(std::shared_ptr<FastCore> core, dds::DataWriter* w, const FastType& type)
      : Endpoint(std::move(core)), writer_(w), type_(type), sample_(type.make_sample()) {}
  ~FastSampleWriter() override { core_->delete_writer(writer_); }
  void write(const SampleHeader& header, std::span<const double> values) override {
    if (values.size() != type_.topic_type().fields.size())
      throw std::logic_error("write " + type_.topic_type().idl_name + ": wrong number of values");
    sample_->store(header, values);
    // Blocks while the KEEP_ALL history is full, up to the reliability's max_blocking_time.
    if (!writer_->write(sample_->data())) fail("write " + type_.topic_type().idl_name);
  }
  int matched_readers() const override {
    return std::max(0, publication_matched(writer_) - core_->domain->tool_readers.on_topic(writer_->get_topic()->get_name()));
  }
  int matched_readers_including_tools() const override { return publication_matched(writer_); }
  // Waits at most 1 s, whatever the caller allows: Fast DDS 2.9 does not act on Cyclone
  // DDS's disposal of a reader or participant (measured: a Fast DDS writer still counts a
  // Cyclone reader whose process has exited as matched until the Cyclone lease expires,
  // 10 s later). At the end of a mixed run a Cyclone partner that finished first may leave
  // without acknowledging our last sample (it did not need it), and waiting for it would
  // outlast the launcher's hang timeout. A live reader acknowledges within a few heartbeat
  // periods (10 ms each). Polled in slices, so a reader that does get unmatched stops
  // counting at once.
  void flush(std::chrono::nanoseconds timeout) override {
    const auto deadline = std::chrono::steady_clock::now() + std::min<std::chrono::nanoseconds>(timeout, std::chrono::seconds(1));
    while (writer_->wait_for_acknowledgments(to_duration(std::chrono::milliseconds(20))) != ReturnCode::RETCODE_OK)
      if (std::chrono::steady_clock::now() > deadline) {
        std::fprintf(stderr, "warning: Fast DDS: %s: not every one of %d matched readers acknowledged the last samples\n",
                     writer_->get_topic()->get_name().c_str(), matched_readers());
        return;
      }
  }

 private:
  dds::DataWriter* writer_;
  const FastType& type_;
  std::unique_ptr<FastSample> sample_;
};

class FastSampleReader final : public SampleReader, Endpoint {
 public:
  FastSampleReader(std::shared_ptr<FastCore> core, dds::DataReader* r, const FastType& type)
      : Endpoint(std::move(core)), reader_(r), condition_(core_->attach(r)), sample_(type.make_sample()) {}
  ~FastSampleReader() override { core_->delete_reader(reader_, condition_); }
  bool take(SampleHeader& header, std::vector<double>& values) override {
    if (!take_one(reader_, sample_->data())) return false;
    sample_->load(header, values);
    return true;
  }
  int matched_writers() const override { return subscription_matched(reader_); }

 private:
  dds::DataReader* reader_;
  dds::ReadCondition* condition_;
  std::unique_ptr<FastSample> sample_;
};

class FastControlWriter final : public ControlWriter, Endpoint {
 public:
  FastControlWriter(std::shared_ptr<FastCore> core, dds::DataWriter* w) : Endpoint(std::move(core)), writer_(w) {}
  ~FastControlWriter() override { core_->delete_writer(writer_); }
  void write(const ControlMessage& m) override {
    mechsim::msg::Control c;
    c.header().run_id(m.run_id);
    c.command(static_cast<std::int32_t>(m.command));
    c.end_time(m.end_time);
    c.macro_step(m.macro_step);
    c.mode(static_cast<std::int32_t>(m.mode));
    c.rtf(m.rtf);
    c.start_wall_ns(m.start_wall_ns);
    c.header().step(m.step);
    c.generation(m.generation);
    if (!writer_->write(&c)) fail("write control");
  }
  int matched_readers() const override { return publication_matched(writer_); }
  std::string guid() const override { return guid_text(writer_->guid()); }

 private:
  dds::DataWriter* writer_;
};

class FastControlReader final : public ControlReader, Endpoint {
 public:
  FastControlReader(std::shared_ptr<FastCore> core, dds::DataReader* r)
      : Endpoint(std::move(core)), reader_(r), condition_(core_->attach(r)) {}
  ~FastControlReader() override { core_->delete_reader(reader_, condition_); }
  std::optional<ControlMessage> take() override {
    mechsim::msg::Control c;
    dds::SampleInfo info;
    if (!take_one(reader_, &c, &info)) return std::nullopt;
    ControlMessage m;
    m.writer = guid_text(info.sample_identity.writer_guid());
    m.run_id = c.header().run_id();
    m.command = static_cast<ControlCommand>(c.command());
    m.end_time = c.end_time();
    m.macro_step = c.macro_step();
    m.mode = static_cast<RunMode>(c.mode());
    m.rtf = c.rtf();
    m.start_wall_ns = c.start_wall_ns();
    m.step = c.header().step();
    m.generation = c.generation();
    return m;
  }

  int matched_writers() const override { return subscription_matched(reader_); }

 private:
  dds::DataReader* reader_;
  dds::ReadCondition* condition_;
};

class FastStatusWriter final : public StatusWriter, Endpoint {
 public:
  FastStatusWriter(std::shared_ptr<FastCore> core, dds::DataWriter* w) : Endpoint(std::move(core)), writer_(w) {}
  ~FastStatusWriter() override { core_->delete_writer(writer_); }
  void write(const StatusMessage& m) override {
    mechsim::msg::Status s;
    s.header().run_id(m.header.run_id);
    s.header().step(m.header.step);
    s.header().t(m.header.t);
    std::string node, message;
    copy_bounded(node, m.node, 64);  // string<64> node, string<256> message in status.idl
    copy_bounded(message, m.message, 256);
    s.node(node);
    s.state(static_cast<std::int32_t>(m.state));
    s.wall_time(m.wall_time);
    s.solver_steps(m.solver_steps);
    s.rhs_evals(m.rhs_evals);
    s.error_test_failures(m.error_test_failures);
    s.nonlinear_failures(m.nonlinear_failures);
    s.roots_found(m.roots_found);
    s.last_step_size(m.last_step_size);
    s.last_order(m.last_order);
    s.lateness_max(m.lateness_max);
    s.lateness_p99(m.lateness_p99);
    s.missed_deadlines(m.missed_deadlines);
    s.rtf_window(m.rtf_window);
    s.readers_matched(m.readers_matched);
    s.message(message);
    s.rollback_step(m.rollback_step);
    s.generation(m.generation);
    s.warning(static_cast<std::int32_t>(m.warning));
    s.error(static_cast<std::int32_t>(m.error));
    writer_->write(&s);  // best effort: a lost heartbeat is harmless
  }

 private:
  dds::DataWriter* writer_;
};

class FastStatusReader final : public StatusReader, Endpoint {
 public:
  FastStatusReader(std::shared_ptr<FastCore> core, dds::DataReader* r)
      : Endpoint(std::move(core)), reader_(r), condition_(core_->attach(r)) {}
  ~FastStatusReader() override { core_->delete_reader(reader_, condition_); }
  std::optional<StatusMessage> take() override {
    mechsim::msg::Status s;
    if (!take_one(reader_, &s)) return std::nullopt;
    StatusMessage m;
    m.header = {s.header().run_id(), s.header().step(), s.header().t()};
    m.node = s.node().to_string();
    m.state = static_cast<NodeState>(s.state());
    m.wall_time = s.wall_time();
    m.solver_steps = s.solver_steps();
    m.rhs_evals = s.rhs_evals();
    m.error_test_failures = s.error_test_failures();
    m.nonlinear_failures = s.nonlinear_failures();
    m.roots_found = s.roots_found();
    m.last_step_size = s.last_step_size();
    m.last_order = s.last_order();
    m.lateness_max = s.lateness_max();
    m.lateness_p99 = s.lateness_p99();
    m.missed_deadlines = s.missed_deadlines();
    m.rtf_window = s.rtf_window();
    m.readers_matched = s.readers_matched();
    m.message = s.message().to_string();
    m.rollback_step = s.rollback_step();
    m.generation = s.generation();
    m.warning = static_cast<NodeWarning>(s.warning());
    m.error = static_cast<NodeError>(s.error());
    return m;
  }

 private:
  dds::DataReader* reader_;
  dds::ReadCondition* condition_;
};

class FastAgentWriter final : public AgentWriter, Endpoint {
 public:
  FastAgentWriter(std::shared_ptr<FastCore> core, dds::DataWriter* w) : Endpoint(std::move(core)), writer_(w) {}
  ~FastAgentWriter() override { core_->delete_writer(writer_); }
  void write(const AgentMessage& m) override {
    if (m.data.size() > kAgentChunkBytes) throw std::logic_error("agent message: more than kAgentChunkBytes of data");
    mechsim::msg::AgentMessage a;
    a.header().run_id(m.run_id);
    a.header().step(m.sequence);
    a.kind(m.kind);
    std::string host, node;
    copy_bounded(host, m.host, 64);  // string<64> host, node in agent.idl
    copy_bounded(node, m.node, 64);
    a.host(host);
    a.node(node);
    a.text(m.text);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(m.data.data());
    a.data(std::vector<std::uint8_t>(bytes, bytes + m.data.size()));
    if (!writer_->write(&a)) fail("write agent message");
  }
  int matched_readers() const override { return publication_matched(writer_); }

 private:
  dds::DataWriter* writer_;
};

class FastAgentReader final : public AgentReader, Endpoint {
 public:
  FastAgentReader(std::shared_ptr<FastCore> core, dds::DataReader* r)
      : Endpoint(std::move(core)), reader_(r), condition_(core_->attach(r)) {}
  ~FastAgentReader() override { core_->delete_reader(reader_, condition_); }
  std::optional<AgentMessage> take() override {
    mechsim::msg::AgentMessage a;
    if (!take_one(reader_, &a)) return std::nullopt;
    AgentMessage m;
    m.run_id = a.header().run_id();
    m.sequence = a.header().step();
    m.kind = a.kind();
    m.host = a.host().to_string();
    m.node = a.node().to_string();
    m.text = a.text();
    const auto* bytes = reinterpret_cast<const std::byte*>(a.data().data());
    m.data.assign(bytes, bytes + a.data().size());
    return m;
  }

 private:
  dds::DataReader* reader_;
  dds::ReadCondition* condition_;
};

}  // namespace

void clean_shared_memory() {
  // The shared-memory transport's segments (fastrtps_*) whose owner is gone: fastdds-tools
  // knows them by their lock files, and leaves the segments of live processes alone.
  if (std::system("command -v fastdds >/dev/null 2>&1") == 0 && std::system("fastdds shm clean >/dev/null 2>&1") != 0)
    std::fprintf(stderr, "mechsim: 'fastdds shm clean' failed; stale Fast DDS segments may remain in /dev/shm\n");
}

FastDomainParticipant::FastDomainParticipant(int domain_id, const std::optional<SecurityIdentity>& security) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  // The default profile of FASTRTPS_DEFAULT_PROFILES_FILE if set, plus the security
  // properties of the identity (docs/security.md).
  // load_profiles() first: the factory reads the XML file only then, and before it the
  // default QoS is Fast DDS's own (every interface; a mixed run never finds Cyclone on lo).
  factory->load_profiles();
  dds::DomainParticipantQos qos = factory->get_default_participant_qos();
  if (security)
    for (const auto& [name, value] : security_properties(*security, "fastdds")) qos.properties().properties().emplace_back(name, value);
  participant = check(factory->create_participant(static_cast<dds::DomainId_t>(domain_id), qos, &tool_readers, dds::StatusMask::none()),
                      "create participant on domain " + std::to_string(domain_id) +
                          (security ? " with DDS security identity '" + security->name + "' of " + security->dir : std::string()) +
                          (std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE")
                               ? std::string(" (profiles from ") + std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE") + ")"
                               : std::string()));
  publisher = check(participant->create_publisher(dds::PUBLISHER_QOS_DEFAULT), "create publisher");
  subscriber = check(participant->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT), "create subscriber");
}

namespace {

// The DomainParticipants shared in this process, by domain and identity: a process group's
// members each get a FastParticipant of their own (own waitset, own endpoints) on one
// DomainParticipant, so the process has one set of Fast DDS threads, ports and discovery
// instead of one per member (docs/performance.md). Weak: the last member to go deletes it.
std::shared_ptr<FastDomainParticipant> shared_domain_participant(int domain_id, const std::optional<SecurityIdentity>& security) {
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<FastDomainParticipant>> shared;
  const std::string key = std::to_string(domain_id) + (security ? "|" + security->dir + "|" + security->name + "|" + security->protection : "");
  std::lock_guard lock(mutex);
  if (auto existing = shared[key].lock()) return existing;
  auto created = std::make_shared<FastDomainParticipant>(domain_id, security);
  shared[key] = created;
  return created;
}

}  // namespace

FastParticipant::FastParticipant(int domain_id, const std::optional<SecurityIdentity>& security, bool share_in_process)
    : core_(std::make_shared<FastCore>(share_in_process ? shared_domain_participant(domain_id, security)
                                                        : std::make_shared<FastDomainParticipant>(domain_id, security))) {}

FastParticipant::~FastParticipant() = default;

std::unique_ptr<SampleWriter> FastParticipant::create_writer(const std::string& topic, const TopicType& type) {
  const FastType& ft = fast_type(type);
  dds::DataWriter* w = core_->writer(topic, ft.make_type_support(), data_qos);
  return std::make_unique<FastSampleWriter>(core_, w, ft);
}

std::unique_ptr<SampleReader> FastParticipant::create_reader(const std::string& topic, const TopicType& type) {
  const FastType& ft = fast_type(type);
  dds::DataReader* r = core_->reader(topic, ft.make_type_support(), data_qos);
  return std::make_unique<FastSampleReader>(core_, r, ft);
}

std::unique_ptr<SampleWriter> FastParticipant::create_redundant_writer(const std::string& topic, const TopicType& type) {
  const FastType& ft = fast_type(type);
  dds::DataWriter* w = core_->writer(redundant_topic(topic), ft.make_type_support(), redundant_qos);
  return std::make_unique<FastSampleWriter>(core_, w, ft);
}

std::unique_ptr<SampleReader> FastParticipant::create_redundant_reader(const std::string& topic, const TopicType& type) {
  const FastType& ft = fast_type(type);
  dds::DataReader* r = core_->reader(redundant_topic(topic), ft.make_type_support(), redundant_qos);
  return std::make_unique<FastSampleReader>(core_, r, ft);
}

std::unique_ptr<ControlWriter> FastParticipant::create_control_writer() {
  return std::make_unique<FastControlWriter>(core_, core_->writer(kControlTopic, new mechsim::msg::ControlPubSubType(), control_qos));
}

std::unique_ptr<ControlReader> FastParticipant::create_control_reader() {
  return std::make_unique<FastControlReader>(core_, core_->reader(kControlTopic, new mechsim::msg::ControlPubSubType(), control_qos));
}

std::unique_ptr<StatusWriter> FastParticipant::create_status_writer() {
  return std::make_unique<FastStatusWriter>(core_, core_->writer(kStatusTopic, new mechsim::msg::StatusPubSubType(), status_qos));
}

std::unique_ptr<StatusReader> FastParticipant::create_status_reader() {
  return std::make_unique<FastStatusReader>(core_, core_->reader(kStatusTopic, new mechsim::msg::StatusPubSubType(), status_qos));
}

std::unique_ptr<AgentWriter> FastParticipant::create_agent_writer(const std::string& topic) {
  return std::make_unique<FastAgentWriter>(core_, core_->writer(topic, new mechsim::msg::AgentMessagePubSubType(), agent_qos));
}

std::unique_ptr<AgentReader> FastParticipant::create_agent_reader(const std::string& topic) {
  return std::make_unique<FastAgentReader>(core_, core_->reader(topic, new mechsim::msg::AgentMessagePubSubType(), agent_qos));
}

bool FastParticipant::wait(std::chrono::nanoseconds timeout) {
  dds::ConditionSeq active;
  const ReturnCode rc = core_->waitset.wait(active, to_duration(timeout));
  if (rc == ReturnCode::RETCODE_TIMEOUT) return false;
  if (rc != ReturnCode::RETCODE_OK) fail("waitset wait");
  if (std::find(active.begin(), active.end(), &core_->guard) != active.end()) core_->guard.set_trigger_value(false);
  return true;
}

void FastParticipant::wake() { core_->guard.set_trigger_value(true); }

}  // namespace mechsim::transport::fastdds
