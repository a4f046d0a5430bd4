// Real-time mode: pacing never changes the numbers, a paced run takes (t_end - t0)/rtf of
// wall time, and an impossible real-time factor stops the run with the measured maximum.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
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

TEST_F(Realtime, EveryPublicationIsInTheLatenessHistogramAndThePngIsWritten) {
  // 0.5 s at 1 ms: 501 publications per node (step 0 included). The histogram's bins and
  // its overflow count every one of them, and its p99 lies between the median and the max.
  std::vector<std::string> args = launch_args(scene_path("cam_press_rt.yaml"), "rt", {"--end", "0.5 s"});
  args.erase(std::find(args.begin(), args.end(), "--no-plot"));
  CommandResult r = run(args, log("rt"), 60);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = summary("rt");
  for (const char* node : {"cam", "follower"}) {
    const json& f = s["realtime"]["nodes"][node];
    long counted = f["lateness_histogram"]["overflow"].get<long>();
    for (const auto& bin : f["lateness_histogram"]["bins"]) counted += bin[1].get<long>();
    EXPECT_EQ(f["publications"].get<long>(), 501) << node;
    EXPECT_EQ(counted, 501) << node;
    EXPECT_LE(f["lateness_median_s"].get<double>(), f["lateness_p99_s"].get<double>());
    EXPECT_LE(f["lateness_p99_s"].get<double>(), f["lateness_max_s"].get<double>() + 1e-6);
    EXPECT_GE(f["period_jitter_std_s"].get<double>(), 0.0);
    EXPECT_GE(f["period_jitter_max_s"].get<double>(), f["period_jitter_std_s"].get<double>());
    EXPECT_TRUE(fs::exists(folder("rt") / (std::string(node) + ".lateness.png"))) << node;
  }
  EXPECT_EQ(s["files"]["lateness_png"].size(), 2u);
}

// Real-time process settings. CI runs as root: the settings are applied and reported; the
// refusal is shown by running the launcher without capabilities and with RLIMIT_RTPRIO 0
// (setpriv, prlimit), still as root so that it can read the build tree wherever it is.
TEST_F(Realtime, ProcessSettingsAreAppliedAndReportedPerNode) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root (SCHED_FIFO, mlockall); the refusal test covers an unprivileged user";
  // cam_press_rt asks for SCHED_FIFO 50 and locked memory; the follower is pinned to CPU 0 here.
  std::string text = slurp(scene_path("cam_press_rt.yaml"));
  text.replace(text.find("    type: follower\n"), 19, "    type: follower\n    realtime: {cpus: [0], priority: 20}\n");
  const std::string scene = (dir_ / "pinned.yaml").string();
  std::ofstream(scene) << text;
  CommandResult r = run(launch_args(scene, "rt", {"--end", "0.3 s"}), log("rt"), 60);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json applied = summary("rt")["process_realtime"];
  EXPECT_EQ(applied["cam"]["policy"], "SCHED_FIFO");
  EXPECT_EQ(applied["cam"]["priority"], 50);
  EXPECT_EQ(applied["cam"]["memory_locked"], true);
  EXPECT_TRUE(applied["cam"]["cpus"].empty());
  EXPECT_EQ(applied["follower"]["priority"], 20);        // the participant's key over the scene's
  EXPECT_EQ(applied["follower"]["memory_locked"], true);  // the scene's, not overridden
  EXPECT_EQ(applied["follower"]["cpus"], json::array({0}));
  EXPECT_NE(r.output.find("process follower"), std::string::npos) << r.output;
}

TEST_F(Realtime, SettingsTheProcessMayNotApplyAreRefusedBeforeAnyNodeStarts) {
  std::vector<std::string> args = launch_args(scene_path("cam_press_rt.yaml"), "rt", {"--end", "0.3 s"});
  if (::geteuid() == 0) {
    if (::access("/usr/bin/setpriv", X_OK) != 0 || ::access("/usr/bin/prlimit", X_OK) != 0)
      GTEST_SKIP() << "setpriv/prlimit (util-linux) missing: cannot drop the capabilities";
    // No capabilities (an empty bounding set: root execs with none), RLIMIT_RTPRIO 0:
    // SCHED_FIFO 50 is not allowed.
    args.insert(args.begin(), {"/usr/bin/setpriv", "--inh-caps=-all", "--ambient-caps=-all", "--bounding-set=-all",
                               "/usr/bin/prlimit", "--rtprio=0", "--memlock=65536", "--"});
  } else {
    rlimit rt{};
    getrlimit(RLIMIT_RTPRIO, &rt);
    if (rt.rlim_cur == RLIM_INFINITY || rt.rlim_cur >= 50) GTEST_SKIP() << "this user may use SCHED_FIFO 50 (RLIMIT_RTPRIO)";
  }
  CommandResult r = run(args, log("rt"), 60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("realtime.priority: SCHED_FIFO priority 50 needs CAP_SYS_NICE (root has it) or RLIMIT_RTPRIO >= 50"),
            std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nothing was started"), std::string::npos) << r.output;
  // Refused before anything started: not even a run folder.
  EXPECT_FALSE(fs::exists(dir_ / "rt") && !fs::is_empty(dir_ / "rt"));
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
