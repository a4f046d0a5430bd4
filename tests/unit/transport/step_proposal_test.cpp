// StepProposal (idl/step.idl) through every backend of this build, typed writer to typed
// reader: the header and every field arrive intact, the boolean as 0/1 and the NaN that
// event_time, error_estimate and state_event_time carry by design included.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "loopback_helpers.h"
#include "mechsim/transport/backends.h"

namespace mechsim::transport {
namespace {

using testing::test_domain;
using testing::wait_until;

std::vector<std::string> vendors() {
  std::vector<std::string> v{"inproc"};
  for (const std::string& vendor : available_vendors()) v.push_back(vendor);
  return v;
}

class StepProposalRoundTrip : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1); }
};

TEST_P(StepProposalRoundTrip, ValuesArriveIntactNaNIncluded) {
  const TopicType* type = find_topic_type("StepProposal");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type, find_topic_type("mechsim::msg::StepProposal"));
  auto a = create_participant(GetParam(), test_domain());
  auto b = create_participant(GetParam(), test_domain());
  const std::string topic = "steptest" + std::to_string(::getpid()) + "/" + GetParam() + "/step";
  auto writer = a->create_writer(topic, *type);
  auto reader = b->create_reader(topic, *type);
  ASSERT_TRUE(wait_until(*a, [&] { return writer->matched_readers() == 1 && reader->matched_writers() == 1; }));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> first(type->fields.size()), second(type->fields.size());
  first[type->field_index("step_length")] = 2.5e-4;
  first[type->field_index("event")] = 0.0;
  first[type->field_index("event_time")] = nan;
  first[type->field_index("error_estimate")] = nan;
  first[type->field_index("state_event_time")] = nan;
  second[type->field_index("step_length")] = 1.0 / 3.0;
  second[type->field_index("event")] = 1.0;
  second[type->field_index("event_time")] = 0.123456789012345;
  second[type->field_index("error_estimate")] = 0.75;
  second[type->field_index("state_event_time")] = 0.0071234567890123;
  writer->write({42, 7, 0.007}, first);
  writer->write({42, 8, 0.00725}, second);

  SampleHeader h;
  std::vector<double> got;
  ASSERT_TRUE(wait_until(*b, [&] { return reader->take(h, got); }));
  EXPECT_EQ(h.run_id, 42u);
  EXPECT_EQ(h.step, 7u);
  EXPECT_EQ(h.t, 0.007);
  ASSERT_EQ(got.size(), first.size());
  EXPECT_EQ(got[type->field_index("step_length")], 2.5e-4);
  EXPECT_EQ(got[type->field_index("event")], 0.0);
  EXPECT_TRUE(std::isnan(got[type->field_index("event_time")]));
  EXPECT_TRUE(std::isnan(got[type->field_index("error_estimate")]));
  EXPECT_TRUE(std::isnan(got[type->field_index("state_event_time")]));

  ASSERT_TRUE(wait_until(*b, [&] { return reader->take(h, got); }));
  EXPECT_EQ(h.step, 8u);
  EXPECT_EQ(h.t, 0.00725);
  EXPECT_EQ(got, second);
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, StepProposalRoundTrip, ::testing::ValuesIn(vendors()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

}  // namespace
}  // namespace mechsim::transport
