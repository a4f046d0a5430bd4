// The raw-CDR seam against the typed one, over loopback Cyclone DDS: what the typed
// writers put on the wire decodes (cdr_decoder.h) to exactly the values written, for every
// mechsim type; raw bytes published again arrive unchanged and typed readers understand
// them; discovery reports the endpoints.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <optional>

#include "cdr_decoder.h"
#include "mechsim/transport/domain_lock.h"
#include "mechsim/transport/backends.h"
#include "mechsim/transport/raw.h"

namespace mechsim::recorder {
namespace {

using namespace std::chrono_literals;

bool wait_until(transport::RawParticipant& p, const std::function<bool()>& done) {
  for (int i = 0; i < 1000; ++i) {
    if (done()) return true;
    p.wait(10ms);
  }
  return done();
}

class RawCdr : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
    typed_ = transport::create_participant("cyclone", domain_.domain_id());
    raw_ = transport::create_raw_participant("cyclone", domain_.domain_id());
  }
  std::string topic(const std::string& what) const { return "rawtest" + std::to_string(::getpid()) + "/" + what; }

  // A domain of its own for this test process (the launcher's flock scheme).
  transport::DomainLock domain_ = transport::DomainLock::acquire();
  std::unique_ptr<transport::Participant> typed_;
  std::unique_ptr<transport::RawParticipant> raw_;
};

// Values that use every bit of a double (no two fields alike), booleans true.
std::vector<double> sample_values(const transport::TopicType& type, int salt) {
  std::vector<double> v(type.fields.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = type.fields[i].kind == transport::FieldKind::boolean ? 1.0 : std::sqrt(2.0 + i) * (salt + 1) - 7.0 * i;
  return v;
}

TEST_F(RawCdr, EveryDataTypeDecodesToTheValuesTheTypedWriterWrote) {
  for (const transport::TopicType* type : transport::all_topic_types()) {
    SCOPED_TRACE(type->idl_name);
    const std::string name = topic(type->idl_name.substr(type->idl_name.rfind(':') + 1));
    auto writer = typed_->create_writer(name, *type);
    auto reader = raw_->create_reader(name, type->idl_name);
    // A raw reader is a tool's reader: the typed writer does not count it as a partner
    // (matched_readers() stays 0), so write until the reader has a sample.
    ASSERT_TRUE(wait_until(*raw_, [&] { return reader->matched_writers() == 1; }));
    EXPECT_EQ(writer->matched_readers(), 0);
    const std::vector<double> values = sample_values(*type, 3);
    transport::RawSample s;
    ASSERT_TRUE(wait_until(*raw_, [&] {
      writer->write({0xfeedfacecafebeefULL, 1234, 1.234}, values);
      return reader->take(s);
    }));
    // Cyclone writes @final types as XCDR1 (docs/dds.md); little endian on this machine.
    ASSERT_GE(s.cdr.size(), 4u);
    EXPECT_EQ(std::to_integer<int>(s.cdr[0]), 0x00);
    EXPECT_EQ(std::to_integer<int>(s.cdr[1]), std::endian::native == std::endian::little ? 0x01 : 0x00);
    EXPECT_EQ(s.header.run_id, 0xfeedfacecafebeefULL);
    EXPECT_EQ(s.header.step, 1234u);
    EXPECT_EQ(s.header.t, 1.234);
    const DecodedSample d = decode_sample(s.cdr, *find_layout(type->idl_name));
    EXPECT_EQ(d.header.run_id, s.header.run_id);
    ASSERT_EQ(d.values.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(as_number(d.values[i]), values[i]) << type->fields[i].name;
  }
}

TEST_F(RawCdr, ControlAndStatusDecodeToWhatWasWritten) {
  auto control = typed_->create_control_writer();
  control->write({77, transport::ControlCommand::start, 2.5, 1e-3, transport::RunMode::realtime, 0.5, 123456789012345, 0, 0, {}});
  auto control_reader = raw_->create_reader(transport::kControlTopic, "Control");  // late joiner: transient local
  transport::RawSample s;
  ASSERT_TRUE(wait_until(*raw_, [&] { return control_reader->take(s); }));
  const MessageLayout& cl = *find_layout("Control");
  DecodedSample c = decode_sample(s.cdr, cl);
  EXPECT_EQ(c.header.run_id, 77u);
  EXPECT_EQ(std::get<std::int64_t>(c.values[cl.field_index("command")]), 1);
  EXPECT_EQ(std::get<double>(c.values[cl.field_index("end_time")]), 2.5);
  EXPECT_EQ(std::get<double>(c.values[cl.field_index("macro_step")]), 1e-3);
  EXPECT_EQ(std::get<std::int64_t>(c.values[cl.field_index("mode")]), 1);
  EXPECT_EQ(std::get<double>(c.values[cl.field_index("rtf")]), 0.5);
  EXPECT_EQ(std::get<std::int64_t>(c.values[cl.field_index("start_wall_ns")]), 123456789012345);

  auto status_reader = raw_->create_reader(transport::kStatusTopic, "mechsim::msg::Status");
  auto status = typed_->create_status_writer();
  transport::StatusMessage m;
  m.header = {78, 9, 0.009};
  m.node = "follower";
  m.state = transport::NodeState::running;
  m.wall_time = 0.125;
  m.solver_steps = 1LL << 40;
  m.rhs_evals = 5;
  m.error_test_failures = 6;
  m.nonlinear_failures = 7;
  m.roots_found = 8;
  m.last_step_size = 3e-5;
  m.last_order = 4;
  m.lateness_max = 2e-3;
  m.missed_deadlines = 11;
  m.rtf_window = 0.875;
  m.readers_matched = 3;
  m.message = "diverged: x";
  ASSERT_TRUE(wait_until(*raw_, [&] {
    status->write(m);  // best effort: repeat until one arrives
    return status_reader->take(s);
  }));
  const MessageLayout& sl = *find_layout("Status");
  DecodedSample d = decode_sample(s.cdr, sl);
  EXPECT_EQ(d.header.step, 9u);
  EXPECT_EQ(d.header.t, 0.009);
  EXPECT_EQ(std::get<std::string>(d.values[sl.field_index("node")]), "follower");
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("state")]), 2);
  EXPECT_EQ(std::get<double>(d.values[sl.field_index("wall_time")]), 0.125);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("solver_steps")]), 1LL << 40);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("rhs_evals")]), 5);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("error_test_failures")]), 6);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("nonlinear_failures")]), 7);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("roots_found")]), 8);
  EXPECT_EQ(std::get<double>(d.values[sl.field_index("last_step_size")]), 3e-5);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("last_order")]), 4);
  EXPECT_EQ(std::get<double>(d.values[sl.field_index("lateness_max")]), 2e-3);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("missed_deadlines")]), 11);
  EXPECT_EQ(std::get<double>(d.values[sl.field_index("rtf_window")]), 0.875);
  EXPECT_EQ(std::get<std::int64_t>(d.values[sl.field_index("readers_matched")]), 3);
  EXPECT_EQ(std::get<std::string>(d.values[sl.field_index("message")]), "diverged: x");
}

TEST_F(RawCdr, RawBytesPublishedAgainArriveUnchangedAndTypedReadersUnderstandThem) {
  const transport::TopicType& type = *transport::find_topic_type("ServoCommand");
  const std::string original = topic("original"), replayed = topic("replayed");
  auto writer = typed_->create_writer(original, type);
  auto raw_in = raw_->create_reader(original, "ServoCommand");
  auto raw_out = raw_->create_writer(replayed, "ServoCommand");
  auto typed_back = typed_->create_reader(replayed, type);
  auto raw_back = raw_->create_reader(replayed, "ServoCommand");
  // Typed writers do not count tools' (raw) readers in matched_readers(); a raw writer
  // counts every reader. Samples for tools' readers are written until they arrive.
  ASSERT_TRUE(wait_until(*raw_, [&] {
    return raw_in->matched_writers() == 1 && raw_out->matched_readers() == 2 && typed_back->matched_writers() == 1 &&
           raw_back->matched_writers() == 1;
  }));
  EXPECT_EQ(writer->matched_readers(), 0);
  const std::vector<double> values = sample_values(type, 5);
  transport::RawSample first, again;
  ASSERT_TRUE(wait_until(*raw_, [&] {
    writer->write({5, 6, 0.006}, values);
    return raw_in->take(first);
  }));
  ASSERT_TRUE(wait_until(*raw_, [&] {
    raw_out->write(first.cdr);
    return raw_back->take(again);
  }));
  EXPECT_EQ(again.cdr, first.cdr);
  transport::SampleHeader h;
  std::vector<double> got;
  ASSERT_TRUE(wait_until(*raw_, [&] { return typed_back->take(h, got); }));
  EXPECT_EQ(h.step, 6u);
  EXPECT_EQ(got, values);

  std::vector<std::byte> garbage(first.cdr.begin(), first.cdr.begin() + 10);  // too short for a ServoCommand
  EXPECT_THROW(raw_out->write(garbage), std::invalid_argument);
  EXPECT_THROW(raw_->create_reader(topic("x"), "NoSuchType"), std::invalid_argument);
}

TEST_F(RawCdr, DiscoveryCountsOtherParticipantsEndpoints) {
  const transport::TopicType& type = *transport::find_topic_type("TachoState");
  const std::string name = topic("discovered");
  auto writer = typed_->create_writer(name, type);
  auto typed_reader = typed_->create_reader(name, type);
  auto own_reader = raw_->create_reader(name, "TachoState");  // our own: not counted
  std::optional<transport::DiscoveredTopic> seen;
  ASSERT_TRUE(wait_until(*raw_, [&] {
    for (const auto& t : raw_->discovered_topics())
      if (t.name == name && t.publishers == 1 && t.subscribers == 1) seen = t;
    return seen.has_value();
  }));
  EXPECT_EQ(seen->type_name, "mechsim::msg::TachoState");
  writer.reset();
  EXPECT_TRUE(wait_until(*raw_, [&] {
    for (const auto& t : raw_->discovered_topics())
      if (t.name == name) return t.publishers == 0;
    return true;
  }));
}

}  // namespace
}  // namespace mechsim::recorder
