// Real-time mode: pacing never changes the numbers, a paced run takes (t_end - t0)/rtf of
// wall time, and an impossible real-time factor stops the run with the measured maximum.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class Realtime : public RunFolderTest {
 protected:
  CommandResult launch(const std::string& tag, std::vector<std::string> extra) {
    return run(launch_args(scene_path("cam_press_rt.yaml"), tag, std::move(extra)), log(tag), 60);
  }
  std::filesystem::path folder(const std::string& tag) const { return run_folder(tag); }
};

TEST_F(Realtime, PacedAndLockStepRunsGiveBitIdenticalOutputs) {
  ASSERT_EQ(launch("rt", {"--end", "1 s", "--rtf", "2"}).exit_code, 0);
  ASSERT_EQ(launch("ls", {"--end", "1 s", "--mode", "lockstep"}).exit_code, 0);
  for (const char* node : {"cam", "follower"}) {
    const std::string name = std::string(node) + ".outputs.bin";
    const std::string paced = slurp((folder("rt") / name).string()), free = slurp((folder("ls") / name).string());
    EXPECT_GT(paced.size(), 1000u * 8u);
    EXPECT_TRUE(paced == free) << name;
  }
  EXPECT_TRUE(summary("rt").contains("realtime"));
  EXPECT_FALSE(summary("ls").contains("realtime"));
}

TEST_F(Realtime, APacedRunTakesSimulatedTimeOverRtfOfWallTime) {
  // 2 s simulated at rtf 2: the last step is due 1 s after step 0. The cam press needs
  // ~1000 steps/s here, a fraction of what lock-step reaches, so a run that keeps up
  // publishes its last step on time to within wake-up jitter: a few percent (5 % = 50 ms).
  CommandResult r = launch("rt", {"--end", "2 s", "--rtf", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json s = summary("rt");
  EXPECT_NEAR(s["realtime"]["paced_wall_time_s"].get<double>(), 1.0, 0.05) << r.output;
  // The launcher's own figure adds the 50 ms between the start command and step 0, and
  // the nodes' tear-down: never less than the paced time.
  EXPECT_GE(s["wall_time_s"].get<double>(), 1.0);
  EXPECT_GE(s["realtime"]["missed_deadlines"].get<long>(), 0);
  EXPECT_TRUE(s["realtime"]["nodes"].contains("cam"));
}

TEST_F(Realtime, AnImpossibleRealTimeFactorAbortsWithTheMeasuredMaximum) {
  // rtf 1000 at 1 ms steps asks for 1e6 steps/s: two orders beyond any lock-step rate.
  CommandResult r = launch("fast", {"--end", "60 s", "--rtf", "1000", "--set", "realtime.on_overrun=abort"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_LT(r.seconds, 10.0);
  EXPECT_TRUE(r.output.find("fell behind its deadline") != std::string::npos ||
              r.output.find("cannot keep up") != std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace mechsim::testing
