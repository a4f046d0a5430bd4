// The in-memory hand-off of a process group's executor (local_handoff.h): a co-located
// reader gets each sample from memory with the values a DDS round trip gives, the writer
// still publishes on its own participant for everyone else, and readiness counts the
// co-located reader and writer as matched. Over the in-process backend, which stands for
// the member's own DDS participant here (it delivers to readers outside the hand-off).
#include <gtest/gtest.h>

#include "mechsim/transport/backends.h"
#include "mechsim/transport/local_handoff.h"

namespace mechsim::transport {
namespace {

constexpr int kDomain = 9101;  // in-process domains are private to this process

const TopicType& follower_state() { return *find_topic_type("FollowerState"); }

TEST(LocalHandoff, ACoLocatedReaderGetsTheSampleFromMemoryAsTheWireWouldCarryIt) {
  LocalHandoff handoff({"follower/state"});
  auto writer_side = handoff.member(create_participant("inproc", kDomain));
  auto reader_side = handoff.member(create_participant("inproc", kDomain));
  auto outside = create_participant("inproc", kDomain);  // another process's reader, say
  const TopicType& type = follower_state();
  auto writer = writer_side->create_writer("follower/state", type);
  auto local = reader_side->create_reader("follower/state", type);
  auto remote = outside->create_reader("follower/state", type);

  // Both readers count; the co-located one is not on the member's own participant, and so
  // no reader on the domain (the launcher's barrier compares with the domain's readers).
  EXPECT_EQ(writer->matched_readers(), 2);
  EXPECT_EQ(writer->matched_readers_on_the_wire(), 1);
  EXPECT_EQ(local->matched_writers(), 1);

  std::vector<double> values(type.fields.size(), 0.25);
  const int contact = type.field_index("contact");
  ASSERT_GE(contact, 0);
  values[contact] = 7.0;  // a boolean travels as true: read back as 1
  writer->write({42, 3, 0.003}, values);

  SampleHeader h;
  std::vector<double> got, got_remote;
  ASSERT_TRUE(local->take(h, got));
  EXPECT_EQ(h.run_id, 42u);
  EXPECT_EQ(h.step, 3u);
  EXPECT_EQ(h.t, 0.003);
  ASSERT_TRUE(remote->take(h, got_remote));
  EXPECT_EQ(got, got_remote);  // the same bytes as through the transport
  EXPECT_EQ(got[contact], 1.0);
  EXPECT_EQ(got[0], 0.25);
  EXPECT_FALSE(local->take(h, got));  // one sample, taken once
}

TEST(LocalHandoff, ATopicNotWrittenInTheProcessIsReadFromTheMembersOwnParticipant) {
  LocalHandoff handoff({"follower/state"});
  auto member = handoff.member(create_participant("inproc", kDomain + 1));
  auto other_process = create_participant("inproc", kDomain + 1);
  const TopicType& cam = *find_topic_type("CamState");
  auto reader = member->create_reader("cam/state", cam);
  EXPECT_EQ(reader->matched_writers(), 0);
  auto writer = other_process->create_writer("cam/state", cam);
  EXPECT_EQ(reader->matched_writers(), 1);
  writer->write({1, 0, 0.0}, std::vector<double>(cam.fields.size(), 2.0));
  SampleHeader h;
  std::vector<double> got;
  ASSERT_TRUE(reader->take(h, got));
  EXPECT_EQ(got, std::vector<double>(cam.fields.size(), 2.0));
}

TEST(LocalHandoff, AWriterThatGoesAwayIsNoLongerMatched) {
  LocalHandoff handoff({"follower/state"});
  auto a = handoff.member(create_participant("inproc", kDomain + 2));
  auto b = handoff.member(create_participant("inproc", kDomain + 2));
  auto reader = b->create_reader("follower/state", follower_state());
  {
    auto first = a->create_writer("follower/state", follower_state());
    auto second = a->create_writer("follower/state", follower_state());
    EXPECT_EQ(reader->matched_writers(), 2);  // the sample gate's second-writer check sees both
  }
  EXPECT_EQ(reader->matched_writers(), 0);
  // The best-effort twin of a local topic brings nothing: the copy is for other hosts.
  auto twin = b->create_redundant_reader("follower/state", follower_state());
  SampleHeader h;
  std::vector<double> got;
  EXPECT_FALSE(twin->take(h, got));
}

// Nobody outside the process reads the topic: the sample is handed over and not published;
// a reader that joins later gets the samples from at most 16 writes on (as a late joiner of
// a VOLATILE topic gets the samples from its match on).
TEST(LocalHandoff, ASampleNobodyOutsideReadsIsNotPublishedUntilAReaderJoins) {
  LocalHandoff handoff({"follower/state"});
  auto a = handoff.member(create_participant("inproc", kDomain + 3));
  auto b = handoff.member(create_participant("inproc", kDomain + 3));
  auto outside = create_participant("inproc", kDomain + 3);
  const TopicType& type = follower_state();
  auto writer = a->create_writer("follower/state", type);
  auto local = b->create_reader("follower/state", type);
  const std::vector<double> values(type.fields.size(), 1.0);
  writer->write({1, 0, 0.0}, values);
  auto late = outside->create_reader("follower/state", type);
  for (std::uint64_t step = 1; step <= 16; ++step) writer->write({1, step, 0.001 * step}, values);
  SampleHeader h;
  std::vector<double> got;
  std::vector<std::uint64_t> published;
  while (late->take(h, got)) published.push_back(h.step);
  ASSERT_FALSE(published.empty());
  EXPECT_GT(published.front(), 0u);        // step 0 went to nobody outside
  EXPECT_EQ(published.back(), 16u);        // from the recheck on, every write
  int handed_over = 0;
  while (local->take(h, got)) ++handed_over;
  EXPECT_EQ(handed_over, 17);              // the co-located reader got every one
}

}  // namespace
}  // namespace mechsim::transport
