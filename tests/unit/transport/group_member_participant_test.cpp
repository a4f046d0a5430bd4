// The members of a process group on Fast DDS share one DomainParticipant
// (create_group_member_participant, backends.h; docs/performance.md): their writers carry one
// GUID prefix, samples pass between them inside the process, and each member keeps a wait()
// of its own, so a member is not woken by another member's samples.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <string>

#include "loopback_helpers.h"
#include "mechsim/transport/backends.h"

namespace mechsim::transport {
namespace {

using testing::test_domain;
using testing::wait_until;

class GroupMemberParticipant : public ::testing::Test {
 protected:
  void SetUp() override {
#ifndef MECHSIM_HAVE_FASTDDS
    GTEST_SKIP() << "built without Fast DDS (MECHSIM_WITH_FASTDDS=OFF)";
#endif
    ::setenv("FASTRTPS_DEFAULT_PROFILES_FILE", MECHSIM_SOURCE_DIR "/config/dds/fastdds-udp.xml", 1);
  }
};

// The GUID prefix (the DomainParticipant's) of a participant's control writer.
std::string guid_prefix(Participant& p) { return p.create_control_writer()->guid().substr(0, 24); }

TEST_F(GroupMemberParticipant, MembersShareOneDomainParticipantAndEachWaitsForItsOwnReaders) {
  auto a = create_group_member_participant("fastdds", test_domain());
  auto b = create_group_member_participant("fastdds", test_domain());
  auto alone = create_participant("fastdds", test_domain());
  EXPECT_EQ(guid_prefix(*a), guid_prefix(*b));
  EXPECT_NE(guid_prefix(*a), guid_prefix(*alone));

  const TopicType& type = *find_topic_type("FollowerState");
  const std::string topic = "test" + std::to_string(::getpid()) + "/group";
  auto writer = a->create_writer(topic, type);
  auto reader = b->create_reader(topic, type);
  ASSERT_TRUE(wait_until(*b, [&] { return writer->matched_readers() == 1 && reader->matched_writers() == 1; }));
  std::vector<double> values(type.fields.size(), 0.25);
  values[type.field_index("contact")] = 1.0;  // a boolean
  writer->write({7, 3, 0.003}, values);
  // b's reader holds the sample from here on (wait() triggers on any sample state)...
  ASSERT_TRUE(wait_until(*b, [&] { return b->wait(std::chrono::milliseconds(0)); }));
  // ...while a, which has no reader, is not woken by it: a wait of its own.
  EXPECT_FALSE(a->wait(std::chrono::milliseconds(50)));
  SampleHeader h;
  std::vector<double> got;
  ASSERT_TRUE(reader->take(h, got));
  EXPECT_EQ(h.step, 3u);
  EXPECT_EQ(got, values);
}

TEST_F(GroupMemberParticipant, AMemberThatLeavesTakesOnlyItsOwnEndpoints) {
  auto b = create_group_member_participant("fastdds", test_domain());
  auto alone = create_participant("fastdds", test_domain());
  const TopicType& type = *find_topic_type("FollowerState");
  const std::string topic = "test" + std::to_string(::getpid()) + "/leave";
  auto reader = b->create_reader(topic, type);
  {
    auto a = create_group_member_participant("fastdds", test_domain());
    auto a_writer = a->create_writer(topic, type);
    ASSERT_TRUE(wait_until(*b, [&] { return reader->matched_writers() == 1; }));
  }
  // a's writer is gone with a; b's DomainParticipant, shared with a until now, lives on.
  ASSERT_TRUE(wait_until(*b, [&] { return reader->matched_writers() == 0; }));
  auto writer = alone->create_writer(topic, type);
  ASSERT_TRUE(wait_until(*b, [&] { return reader->matched_writers() == 1 && writer->matched_readers() == 1; }));
  writer->write({7, 4, 0.004}, std::vector<double>(type.fields.size(), 1.0));
  SampleHeader h;
  std::vector<double> got;
  ASSERT_TRUE(wait_until(*b, [&] { return reader->take(h, got); }));
  EXPECT_EQ(h.step, 4u);
}

}  // namespace
}  // namespace mechsim::transport
