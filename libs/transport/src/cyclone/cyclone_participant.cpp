// Cyclone DDS (C API) backend of the transport seam.
#include "cyclone_participant.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "agent.h"
#include "control.h"
#include "cyclone_qos.h"
#include "cyclone_types.h"
#include "fmu.h"

#include <cstdint>
#include "mechsim/transport/raw.h"
#include "status.h"

namespace mechsim::transport::cyclone {

namespace {

[[noreturn]] void fail(const std::string& what, dds_return_t rc) {
  throw std::runtime_error("Cyclone DDS: " + what + ": " + dds_strretcode(rc));
}

dds_entity_t check(dds_entity_t e, const std::string& what) {
  if (e < 0) fail(what, e);
  return e;
}

void copy_bounded(char* dst, std::size_t capacity, const std::string& src) {
  std::size_t n = std::min(src.size(), capacity - 1);
  std::memcpy(dst, src.data(), n);
  dst[n] = '\0';
}

int publication_matched(dds_entity_t writer) {
  dds_publication_matched_status_t st{};
  return dds_get_publication_matched_status(writer, &st) == DDS_RETCODE_OK ? static_cast<int>(st.current_count) : 0;
}

// Readers matched with `writer` except mechsim's tools' readers (recorder, `topic echo`),
// which carry USER_DATA kToolReaderUserData (raw.h): a node waits for its partners, and a
// recorder started first must not stand in for one.
int partner_readers_matched(dds_entity_t writer) {
  std::vector<dds_instance_handle_t> handles(8);
  dds_return_t n = dds_get_matched_subscriptions(writer, handles.data(), handles.size());
  if (n > static_cast<dds_return_t>(handles.size())) {
    handles.resize(static_cast<std::size_t>(n));
    n = dds_get_matched_subscriptions(writer, handles.data(), handles.size());
  }
  if (n < 0) return 0;
  const std::size_t tag_size = std::strlen(kToolReaderUserData);
  int partners = 0;
  for (std::size_t i = 0; i < std::min(static_cast<std::size_t>(n), handles.size()); ++i) {
    dds_builtintopic_endpoint_t* reader = dds_get_matched_subscription_data(writer, handles[i]);
    if (reader == nullptr) continue;  // unmatched meanwhile
    void* user_data = nullptr;
    size_t size = 0;
    const bool tool = reader->qos != nullptr && dds_qget_userdata(reader->qos, &user_data, &size) &&
                      size == tag_size && std::memcmp(user_data, kToolReaderUserData, size) == 0;
    dds_free(user_data);
    dds_builtintopic_free_endpoint(reader);
    if (!tool) ++partners;
  }
  return partners;
}

// "GUID <hex>, process <name> (pid <n>) on <host>" for every writer matched with `reader`;
// the process and host come from the properties a Cyclone participant announces (other
// vendors' participants announce none).
std::vector<std::string> describe_matched_writers(dds_entity_t reader) {
  std::vector<std::string> out;
  std::vector<dds_instance_handle_t> handles(16);
  const dds_return_t n = dds_get_matched_publications(reader, handles.data(), handles.size());
  if (n <= 0) return out;
  const dds_entity_t pp = dds_get_participant(reader);
  const dds_entity_t participants = dds_create_reader(pp, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, nullptr, nullptr);
  void* samples[64] = {};
  dds_sample_info_t infos[64];
  const dds_return_t np = participants > 0 ? dds_read(participants, samples, infos, 64, 64) : 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(static_cast<std::size_t>(n), handles.size()); ++i) {
    dds_builtintopic_endpoint_t* w = dds_get_matched_publication_data(reader, handles[i]);
    if (w == nullptr) continue;
    std::string text = "GUID " + guid_text(w->key.v);
    for (dds_return_t j = 0; j < np; ++j) {
      const auto* p = static_cast<const dds_builtintopic_participant_t*>(samples[j]);
      if (!infos[j].valid_data || std::memcmp(p->key.v, w->participant_key.v, sizeof p->key.v) != 0) continue;
      char *host = nullptr, *pid = nullptr, *name = nullptr;
      if (p->qos && dds_qget_prop(p->qos, "__Hostname", &host) && dds_qget_prop(p->qos, "__Pid", &pid)) {
        dds_qget_prop(p->qos, "__ProcessName", &name);
        text += std::string(", process ") + (name ? name : "?") + " (pid " + pid + ") on " + host;
      }
      dds_free(host);
      dds_free(pid);
      dds_free(name);
    }
    dds_builtintopic_free_endpoint(w);
    out.push_back(text);
  }
  if (np > 0) dds_return_loan(participants, samples, np);
  if (participants > 0) dds_delete(participants);
  return out;
}

int subscription_matched(dds_entity_t reader) {
  dds_subscription_matched_status_t st{};
  return dds_get_subscription_matched_status(reader, &st) == DDS_RETCODE_OK ? static_cast<int>(st.current_count) : 0;
}

// Takes one sample into `buffer` (a zeroed struct of the topic type); skips invalid
// samples (disposal/unregistration notices). Returns false when none is left.
bool take_one(dds_entity_t reader, void* buffer, dds_sample_info_t* info_out = nullptr) {
  for (;;) {
    void* samples[1] = {buffer};
    dds_sample_info_t info;
    dds_return_t n = dds_take(reader, samples, &info, 1, 1);
    if (n < 0) fail("take", n);
    if (n == 0) return false;
    if (info_out != nullptr) *info_out = info;
    if (info.valid_data) return true;
  }
}

class CycloneSampleWriter final : public SampleWriter {
 public:
  CycloneSampleWriter(dds_entity_t writer, const CycloneType& type)
      : writer_(writer), type_(type), buffer_(type.size, 0) {}
  ~CycloneSampleWriter() override { dds_delete(writer_); }
  void write(const SampleHeader& header, std::span<const double> values) override {
    if (values.size() != type_.slots.size())
      throw std::logic_error("write " + type_.type->idl_name + ": wrong number of values");
    auto* h = reinterpret_cast<mechsim_msg_Header*>(buffer_.data());
    h->run_id = header.run_id;
    h->step = header.step;
    h->t = header.t;
    for (std::size_t i = 0; i < values.size(); ++i) {
      char* p = buffer_.data() + type_.slots[i].offset;
      if (type_.slots[i].kind == FieldKind::f64)
        std::memcpy(p, &values[i], sizeof(double));
      else
        *reinterpret_cast<bool*>(p) = values[i] != 0.0;
    }
    dds_return_t rc = dds_write(writer_, buffer_.data());
    if (rc != DDS_RETCODE_OK) fail("write " + type_.type->idl_name, rc);
  }
  int matched_readers() const override { return partner_readers_matched(writer_); }
  int matched_readers_including_tools() const override { return publication_matched(writer_); }
  void flush(std::chrono::nanoseconds timeout) override { dds_wait_for_acks(writer_, timeout.count()); }

 private:
  dds_entity_t writer_;
  const CycloneType& type_;
  std::vector<char> buffer_;
};

class CycloneSampleReader final : public SampleReader {
 public:
  CycloneSampleReader(dds_entity_t reader, const CycloneType& type)
      : reader_(reader), type_(type), buffer_(type.size, 0) {}
  ~CycloneSampleReader() override { dds_delete(reader_); }
  bool take(SampleHeader& header, std::vector<double>& values) override {
    if (!take_one(reader_, buffer_.data())) return false;
    const auto* h = reinterpret_cast<const mechsim_msg_Header*>(buffer_.data());
    header = {h->run_id, h->step, h->t};
    values.resize(type_.slots.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      const char* p = buffer_.data() + type_.slots[i].offset;
      if (type_.slots[i].kind == FieldKind::f64)
        std::memcpy(&values[i], p, sizeof(double));
      else
        values[i] = *reinterpret_cast<const bool*>(p) ? 1.0 : 0.0;
    }
    return true;
  }
  int matched_writers() const override { return subscription_matched(reader_); }
  std::vector<std::string> matched_writer_ids() const override { return describe_matched_writers(reader_); }

 private:
  dds_entity_t reader_;
  const CycloneType& type_;
  std::vector<char> buffer_;
};

// An FMU participant's topic (layout sequences, idl/fmu.idl): the fields split by kind into
// FmuOutputs' three sequences. The writer lends its own buffers to the sample (_release
// false); the reader's sample owns what Cyclone allocates and frees it at the end.
class CycloneSequenceWriter final : public SampleWriter {
 public:
  CycloneSequenceWriter(dds_entity_t writer, const TopicType& type) : writer_(writer), type_(type), at_(sequence_positions(type)) {
    for (const auto& f : type.fields) {
      if (f.kind == FieldKind::f64) reals_.push_back(0.0);
      else if (f.kind == FieldKind::i32) integers_.push_back(0);
      else booleans_.push_back(0);
    }
  }
  ~CycloneSequenceWriter() override { dds_delete(writer_); }
  void write(const SampleHeader& header, std::span<const double> values) override {
    if (values.size() != type_.fields.size()) throw std::logic_error("write " + type_.idl_name + ": wrong number of values");
    pack_sequences(type_, at_, values.data(), reals_, integers_, booleans_);
    mechsim_msg_FmuOutputs m{};
    m.header = {header.run_id, header.step, header.t};
    m.reals = {static_cast<uint32_t>(reals_.size()), static_cast<uint32_t>(reals_.size()), reals_.data(), false};
    m.integers = {static_cast<uint32_t>(integers_.size()), static_cast<uint32_t>(integers_.size()), integers_.data(), false};
    m.booleans = {static_cast<uint32_t>(booleans_.size()), static_cast<uint32_t>(booleans_.size()),
                  reinterpret_cast<bool*>(booleans_.data()), false};
    dds_return_t rc = dds_write(writer_, &m);
    if (rc != DDS_RETCODE_OK) fail("write " + type_.idl_name, rc);
  }
  int matched_readers() const override { return partner_readers_matched(writer_); }
  int matched_readers_including_tools() const override { return publication_matched(writer_); }
  void flush(std::chrono::nanoseconds timeout) override { dds_wait_for_acks(writer_, timeout.count()); }

 private:
  dds_entity_t writer_;
  TopicType type_;  // a copy: FMU topic types are made per plan
  std::vector<std::size_t> at_;
  std::vector<double> reals_;
  std::vector<std::int32_t> integers_;
  std::vector<char> booleans_;  // bool-sized, unlike std::vector<bool>
  static_assert(sizeof(bool) == sizeof(char));
};

class CycloneSequenceReader final : public SampleReader {
 public:
  CycloneSequenceReader(dds_entity_t reader, const TopicType& type) : reader_(reader), type_(type), at_(sequence_positions(type)) {}
  ~CycloneSequenceReader() override {
    dds_delete(reader_);
    dds_sample_free(&sample_, &mechsim_msg_FmuOutputs_desc, DDS_FREE_CONTENTS);
  }
  bool take(SampleHeader& header, std::vector<double>& values) override {
    if (!take_one(reader_, &sample_)) return false;
    header = {sample_.header.run_id, sample_.header.step, sample_.header.t};
    unpack_sequences(type_, at_, sample_.reals._buffer, sample_.reals._length, sample_.integers._buffer, sample_.integers._length,
                     sample_.booleans._buffer, sample_.booleans._length, values);
    return true;
  }
  int matched_writers() const override { return subscription_matched(reader_); }
  std::vector<std::string> matched_writer_ids() const override { return describe_matched_writers(reader_); }

 private:
  dds_entity_t reader_;
  TopicType type_;
  std::vector<std::size_t> at_;
  mechsim_msg_FmuOutputs sample_{};
};

class CycloneControlWriter final : public ControlWriter {
 public:
  explicit CycloneControlWriter(dds_entity_t w) : writer_(w) {}
  ~CycloneControlWriter() override { dds_delete(writer_); }
  void write(const ControlMessage& m) override {
    mechsim_msg_Control c{};
    c.header.run_id = m.run_id;
    c.command = static_cast<int32_t>(m.command);
    c.end_time = m.end_time;
    c.macro_step = m.macro_step;
    c.mode = static_cast<int32_t>(m.mode);
    c.rtf = m.rtf;
    c.start_wall_ns = m.start_wall_ns;
    c.header.step = m.step;
    c.generation = m.generation;
    dds_return_t rc = dds_write(writer_, &c);
    if (rc != DDS_RETCODE_OK) fail("write control", rc);
  }
  int matched_readers() const override { return publication_matched(writer_); }
  std::string guid() const override {
    dds_guid_t g;
    if (dds_get_guid(writer_, &g) != DDS_RETCODE_OK) return {};
    return guid_text(g.v);
  }

 private:
  dds_entity_t writer_;
};

class CycloneControlReader final : public ControlReader {
 public:
  explicit CycloneControlReader(dds_entity_t r) : reader_(r) {}
  ~CycloneControlReader() override { dds_delete(reader_); }
  std::optional<ControlMessage> take() override {
    mechsim_msg_Control c{};
    dds_sample_info_t info;
    if (!take_one(reader_, &c, &info)) return std::nullopt;
    ControlMessage m{c.header.run_id, static_cast<ControlCommand>(c.command), c.end_time,
                     c.macro_step, static_cast<RunMode>(c.mode), c.rtf, c.start_wall_ns, c.header.step, c.generation, {}};
    // The sender: its matched-publication data, while it is matched (it is, as it just wrote).
    if (dds_builtintopic_endpoint_t* w = dds_get_matched_publication_data(reader_, info.publication_handle)) {
      m.writer = guid_text(w->key.v);
      dds_builtintopic_free_endpoint(w);
    }
    return m;
  }

  int matched_writers() const override { return subscription_matched(reader_); }
  std::vector<std::string> matched_writer_ids() const override { return describe_matched_writers(reader_); }

 private:
  dds_entity_t reader_;
};

class CycloneStatusWriter final : public StatusWriter {
 public:
  explicit CycloneStatusWriter(dds_entity_t w) : writer_(w) {}
  ~CycloneStatusWriter() override { dds_delete(writer_); }
  void write(const StatusMessage& m) override {
    mechsim_msg_Status s{};
    s.header = {m.header.run_id, m.header.step, m.header.t};
    copy_bounded(s.node, sizeof s.node, m.node);
    s.state = static_cast<int32_t>(m.state);
    s.wall_time = m.wall_time;
    s.solver_steps = m.solver_steps;
    s.rhs_evals = m.rhs_evals;
    s.error_test_failures = m.error_test_failures;
    s.nonlinear_failures = m.nonlinear_failures;
    s.roots_found = m.roots_found;
    s.last_step_size = m.last_step_size;
    s.last_order = m.last_order;
    s.lateness_max = m.lateness_max;
    s.lateness_p99 = m.lateness_p99;
    s.missed_deadlines = m.missed_deadlines;
    s.rtf_window = m.rtf_window;
    s.readers_matched = m.readers_matched;
    copy_bounded(s.message, sizeof s.message, m.message);
    s.rollback_step = m.rollback_step;
    s.generation = m.generation;
    s.warning = static_cast<std::int32_t>(m.warning);
    s.error = static_cast<std::int32_t>(m.error);
    dds_write(writer_, &s);  // best effort: a lost heartbeat is harmless
  }

 private:
  dds_entity_t writer_;
};

class CycloneStatusReader final : public StatusReader {
 public:
  explicit CycloneStatusReader(dds_entity_t r) : reader_(r) {}
  ~CycloneStatusReader() override { dds_delete(reader_); }
  std::optional<StatusMessage> take() override {
    mechsim_msg_Status s{};
    if (!take_one(reader_, &s)) return std::nullopt;
    StatusMessage m;
    m.header = {s.header.run_id, s.header.step, s.header.t};
    m.node = s.node;
    m.state = static_cast<NodeState>(s.state);
    m.wall_time = s.wall_time;
    m.solver_steps = s.solver_steps;
    m.rhs_evals = s.rhs_evals;
    m.error_test_failures = s.error_test_failures;
    m.nonlinear_failures = s.nonlinear_failures;
    m.roots_found = s.roots_found;
    m.last_step_size = s.last_step_size;
    m.last_order = s.last_order;
    m.lateness_max = s.lateness_max;
    m.lateness_p99 = s.lateness_p99;
    m.missed_deadlines = s.missed_deadlines;
    m.rtf_window = s.rtf_window;
    m.readers_matched = s.readers_matched;
    m.message = s.message;
    m.rollback_step = s.rollback_step;
    m.generation = s.generation;
    m.warning = static_cast<NodeWarning>(s.warning);
    m.error = static_cast<NodeError>(s.error);
    return m;
  }

 private:
  dds_entity_t reader_;
};

class CycloneAgentWriter final : public AgentWriter {
 public:
  explicit CycloneAgentWriter(dds_entity_t w) : writer_(w) {}
  ~CycloneAgentWriter() override { dds_delete(writer_); }
  void write(const AgentMessage& m) override {
    if (m.data.size() > kAgentChunkBytes) throw std::logic_error("agent message: more than kAgentChunkBytes of data");
    mechsim_msg_AgentMessage a{};
    a.header.run_id = m.run_id;
    a.header.step = m.sequence;
    a.kind = m.kind;
    copy_bounded(a.host, sizeof a.host, m.host);
    copy_bounded(a.node, sizeof a.node, m.node);
    a.text = const_cast<char*>(m.text.c_str());
    a.data._buffer = reinterpret_cast<uint8_t*>(const_cast<std::byte*>(m.data.data()));
    a.data._length = a.data._maximum = static_cast<uint32_t>(m.data.size());
    a.data._release = false;
    dds_return_t rc = dds_write(writer_, &a);
    if (rc != DDS_RETCODE_OK) fail("write agent message", rc);
  }
  int matched_readers() const override { return publication_matched(writer_); }

 private:
  dds_entity_t writer_;
};

class CycloneAgentReader final : public AgentReader {
 public:
  explicit CycloneAgentReader(dds_entity_t r) : reader_(r) {}
  ~CycloneAgentReader() override { dds_delete(reader_); }
  std::optional<AgentMessage> take() override {
    // The loan-free take with a null buffer pointer lets Cyclone allocate the string and
    // the sequence; dds_return_loan frees them.
    void* samples[1] = {nullptr};
    dds_sample_info_t info;
    for (;;) {
      dds_return_t n = dds_take(reader_, samples, &info, 1, 1);
      if (n < 0) fail("take agent message", n);
      if (n == 0) return std::nullopt;
      if (info.valid_data) break;
      dds_return_loan(reader_, samples, n);
      samples[0] = nullptr;
    }
    const auto* a = static_cast<const mechsim_msg_AgentMessage*>(samples[0]);
    AgentMessage m;
    m.run_id = a->header.run_id;
    m.sequence = a->header.step;
    m.kind = a->kind;
    m.host = a->host;
    m.node = a->node;
    m.text = a->text ? a->text : "";
    const auto* bytes = reinterpret_cast<const std::byte*>(a->data._buffer);
    m.data.assign(bytes, bytes + a->data._length);
    dds_return_loan(reader_, samples, 1);
    return m;
  }

 private:
  dds_entity_t reader_;
};

}  // namespace

CycloneParticipant::CycloneParticipant(int domain_id, const std::optional<SecurityIdentity>& security) {
  participant_ = create_participant_entity(domain_id, security);
  waitset_ = check(dds_create_waitset(participant_), "create waitset");
  guard_ = check(dds_create_guardcondition(participant_), "create guard condition");
  check(dds_waitset_attach(waitset_, guard_, guard_), "attach guard condition");
}

CycloneParticipant::~CycloneParticipant() { dds_delete(participant_); }

dds_entity_t CycloneParticipant::topic(const std::string& name, const dds_topic_descriptor_t* desc) {
  auto it = topics_.find(name);
  if (it != topics_.end()) return it->second;
  dds_entity_t t = check(dds_create_topic(participant_, desc, name.c_str(), nullptr, nullptr),
                         "create topic " + name);
  topics_.emplace(name, t);
  return t;
}

dds_entity_t CycloneParticipant::attach_reader(dds_entity_t reader) {
  dds_entity_t cond = check(dds_create_readcondition(reader, DDS_ANY_STATE), "create read condition");
  check(dds_waitset_attach(waitset_, cond, reader), "attach read condition");
  return reader;
}

std::unique_ptr<SampleWriter> CycloneParticipant::data_writer(const std::string& topic_name, const TopicType& type, bool redundant) {
  Qos qos;
  set_qos(qos, redundant ? QosKind::redundant : QosKind::data);
  const std::string name = redundant ? redundant_topic(topic_name) : topic_name;
  // An FMU participant's topic travels as FmuOutputs (idl/fmu.idl), the others as their own type.
  const bool sequences = type.layout == TopicLayout::sequences;
  const dds_topic_descriptor_t* descriptor = sequences ? &mechsim_msg_FmuOutputs_desc : cyclone_type(type).descriptor;
  dds_entity_t w = check(dds_create_writer(participant_, topic(name, descriptor), qos.q, nullptr), "create writer on " + name);
  if (sequences) return std::make_unique<CycloneSequenceWriter>(w, type);
  return std::make_unique<CycloneSampleWriter>(w, cyclone_type(type));
}

std::unique_ptr<SampleReader> CycloneParticipant::data_reader(const std::string& topic_name, const TopicType& type, bool redundant) {
  Qos qos;
  set_qos(qos, redundant ? QosKind::redundant : QosKind::data);
  const std::string name = redundant ? redundant_topic(topic_name) : topic_name;
  const bool sequences = type.layout == TopicLayout::sequences;
  const dds_topic_descriptor_t* descriptor = sequences ? &mechsim_msg_FmuOutputs_desc : cyclone_type(type).descriptor;
  dds_entity_t r = check(dds_create_reader(participant_, topic(name, descriptor), qos.q, nullptr), "create reader on " + name);
  if (sequences) return std::make_unique<CycloneSequenceReader>(attach_reader(r), type);
  return std::make_unique<CycloneSampleReader>(attach_reader(r), cyclone_type(type));
}

std::unique_ptr<SampleWriter> CycloneParticipant::create_writer(const std::string& topic_name, const TopicType& type) {
  return data_writer(topic_name, type, false);
}

std::unique_ptr<SampleReader> CycloneParticipant::create_reader(const std::string& topic_name, const TopicType& type) {
  return data_reader(topic_name, type, false);
}

std::unique_ptr<SampleWriter> CycloneParticipant::create_redundant_writer(const std::string& topic_name, const TopicType& type) {
  return data_writer(topic_name, type, true);
}

std::unique_ptr<SampleReader> CycloneParticipant::create_redundant_reader(const std::string& topic_name, const TopicType& type) {
  return data_reader(topic_name, type, true);
}

std::unique_ptr<ControlWriter> CycloneParticipant::create_control_writer() {
  Qos qos;
  set_qos(qos, QosKind::control);
  dds_entity_t w = check(dds_create_writer(participant_, topic(kControlTopic, &mechsim_msg_Control_desc), qos.q, nullptr),
                         "create control writer");
  return std::make_unique<CycloneControlWriter>(w);
}

std::unique_ptr<ControlReader> CycloneParticipant::create_control_reader() {
  Qos qos;
  set_qos(qos, QosKind::control);
  dds_entity_t r = check(dds_create_reader(participant_, topic(kControlTopic, &mechsim_msg_Control_desc), qos.q, nullptr),
                         "create control reader");
  return std::make_unique<CycloneControlReader>(attach_reader(r));
}

std::unique_ptr<StatusWriter> CycloneParticipant::create_status_writer() {
  Qos qos;
  set_qos(qos, QosKind::status);
  dds_entity_t w = check(dds_create_writer(participant_, topic(kStatusTopic, &mechsim_msg_Status_desc), qos.q, nullptr),
                         "create status writer");
  return std::make_unique<CycloneStatusWriter>(w);
}

std::unique_ptr<StatusReader> CycloneParticipant::create_status_reader() {
  Qos qos;
  set_qos(qos, QosKind::status);
  dds_entity_t r = check(dds_create_reader(participant_, topic(kStatusTopic, &mechsim_msg_Status_desc), qos.q, nullptr),
                         "create status reader");
  return std::make_unique<CycloneStatusReader>(attach_reader(r));
}

std::unique_ptr<AgentWriter> CycloneParticipant::create_agent_writer(const std::string& topic_name) {
  Qos qos;
  set_qos(qos, QosKind::agent);
  dds_entity_t w = check(dds_create_writer(participant_, topic(topic_name, &mechsim_msg_AgentMessage_desc), qos.q, nullptr),
                         "create writer on " + topic_name);
  return std::make_unique<CycloneAgentWriter>(w);
}

std::unique_ptr<AgentReader> CycloneParticipant::create_agent_reader(const std::string& topic_name) {
  Qos qos;
  set_qos(qos, QosKind::agent);
  dds_entity_t r = check(dds_create_reader(participant_, topic(topic_name, &mechsim_msg_AgentMessage_desc), qos.q, nullptr),
                         "create reader on " + topic_name);
  return std::make_unique<CycloneAgentReader>(attach_reader(r));
}

bool CycloneParticipant::wait(std::chrono::nanoseconds timeout) {
  dds_attach_t triggered[16];
  dds_return_t n = dds_waitset_wait(waitset_, triggered, 16, timeout.count());
  if (n < 0) fail("waitset wait", n);
  for (dds_return_t i = 0; i < std::min<dds_return_t>(n, 16); ++i)
    if (triggered[i] == static_cast<dds_attach_t>(guard_)) {
      bool was = false;
      dds_take_guardcondition(guard_, &was);
    }
  return n > 0;
}

void CycloneParticipant::wake() { dds_set_guardcondition(guard_, true); }

}  // namespace mechsim::transport::cyclone
