// A sample DDS loses and never repairs (the test seam `testing.lose_write_of_step`: the node
// leaves out its write of that step, both copies) must not stall lock step: the node that
// waits writes its newest samples again after 100 ms (StallResend, docs/node-loop.md "Stall
// resend"), its partner drops what it already took, and the run ends as without the loss,
// byte for byte. Without the resend the partner waits for the lost step until the partition
// grace (2 s) ends the run with exit code 1. On real processes over loopback, both vendors.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

using json = nlohmann::json;

class LostSample : public RunFolderTest, public ::testing::WithParamInterface<const char*> {};

// A process per node: the sample is lost between processes (in one process the members hand
// samples over in memory and read the cam's log in the group's).
TEST_P(LostSample, ALostWriteIsSentAgainAndTheRunEndsByteIdentical) {
  const std::string vendor = GetParam();
  const CommandResult whole = run(launch_args_a_process_each(scene_path("cam_press.yaml"), "whole", {"--dds", vendor}), log("whole"), 240);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  // The cam's sample of step 500 (of 2 000) never goes out.
  const CommandResult lossy = run(launch_args_a_process_each(scene_path("cam_press.yaml"), "lossy",
                                              {"--dds", vendor, "--set", "participants.cam.testing.lose_write_of_step=500"}),
                                  log("lossy"), 240);
  ASSERT_EQ(lossy.exit_code, 0) << lossy.output;
  const json s = summary("whole");
  EXPECT_EQ(summary("lossy")["steps"], s["steps"]);
  expect_identical_node_outputs(run_folder("whole"), run_folder("lossy"), s, "a run and the same run with a lost sample");
  // The cam, waiting for the follower's next step, said that it sent its newest samples again.
  EXPECT_NE(slurp((run_folder("lossy") / "cam.log").string()).find("lock step: no step for"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Vendors, LostSample, ::testing::Values("cyclone", "fastdds"),
                         [](const ::testing::TestParamInfo<const char*>& i) { return std::string(i.param); });

}  // namespace
}  // namespace mechsim::testing
