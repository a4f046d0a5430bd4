// `mechsim launch` end to end: real node processes over loopback DDS (each run on its own
// domain), compared with the monolithic reference; failure paths leave nothing behind.
#include <signal.h>

#include <gtest/gtest.h>

#include "mechsim/cosim/output_log.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kCamPress = scene_path("cam_press.yaml");

class Launch : public RunFolderTest {
 protected:
  // A process per node: these tests kill, stop and read the logs of the cam's and the
  // follower's processes (the default layout is checked in placement_test.cpp).
  std::vector<std::string> launch_args(const std::string& tag, std::vector<std::string> extra = {}) const {
    return RunFolderTest::launch_args_a_process_each(kCamPress, tag, std::move(extra));
  }
};

TEST_F(Launch, CamPressRunsDistributedAndReproducesTheReference) {
  CommandResult r = run(launch_args("a"), log("a"), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json s = summary("a");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["scene"], "cam_press");
  // 2000 steps of 1 ms, and one landed on each load boundary off the grid (100, 120, 210 deg).
  EXPECT_EQ(s["steps"], 2003);
  EXPECT_EQ(s["scheduled_events"].size(), 5u);
  EXPECT_DOUBLE_EQ(s["simulated_time_s"].get<double>(), 2.0);
  EXPECT_GT(s["steps_per_second"].get<double>(), 0.0);
  EXPECT_EQ(s["provenance"]["scene_sha256"].get<std::string>().size(), 64u);
  // Gauss-Seidel edge cam -> follower: the follower computes from the cam's values of the
  // same step, exactly as the monolithic reference does, with the same blocks: the
  // contact force must agree to the last bit (any protocol slip would cost newtons).
  EXPECT_EQ(s["signals"]["follower.contact_force"]["max_abs_error"].get<double>(), 0.0);
  EXPECT_EQ(s["signals"]["follower.drive_torque"]["max_abs_error"].get<double>(), 0.0);
  // Jacobi edge follower -> cam, held: the cam reports the drive torque one macro step
  // late. At the load boundaries the steps land on the jump and the cam's row there is
  // evaluated after it (with the follower's sample of that instant), so what is left is the
  // one-step lag of a smooth torque: 0.475 % of range, the figure the launcher gave "away
  // from the jumps" before the steps landed on them (and it halves with H: bench order 0.99).
  // A jump crossed one step late costs 24.5 % (the error before this landed). 1 % is the
  // issue's target and well apart from both.
  const double lag_max = s["signals"]["cam.shaft_torque"]["max_rel_error"].get<double>();
  EXPECT_GT(lag_max, 0.0);
  EXPECT_LT(lag_max, 0.01);
  // Spec cam.md §3: with k = 9 N/mm and F0 = 125 N the contact force stays positive over
  // the whole cycle; its minimum lies at the end of the fall under the -120 N load.
  const json& min_n = s["report"][0];
  EXPECT_EQ(min_n["signal"], "follower.contact_force");
  EXPECT_GT(min_n["value"].get<double>(), 0.0);
  EXPECT_GE(min_n["at"]["value"].get<double>(), 180.0);
  EXPECT_LT(min_n["at"]["value"].get<double>(), 210.0);
  // The run folder holds what the user is told it holds.
  const fs::path folder = run_folder("a");
  for (const char* f : {"summary.json", "scene.yaml", "cam.log", "follower.log", "signals.csv"})
    EXPECT_TRUE(fs::exists(folder / f)) << f;
}

// The same press with an adaptive macro step (config/scenes/cam_press_adaptive.yaml): the
// issue's target for the default press, under 1 % of range with no more macro steps than the
// fixed grid's 2000. Measured: 301 steps, 0.434 % (with the drive torque held, as
// cam_press.yaml ships it: 582 steps, 0.439 %).
TEST_F(Launch, TheAdaptivePressStaysUnderOnePercentWithFewerStepsThanTheFixedGrid) {
  CommandResult r = run(RunFolderTest::launch_args(scene_path("cam_press_adaptive.yaml"), "a"), log("a"), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = summary("a");
  const auto steps = s["steps"].get<std::uint64_t>();
  // The fixed 1 ms grid takes 2003 steps for 0.475 %; the adaptive one keeps the error under
  // 0.8 tol x scale = 0.08 N m (0.41 % of the 19.3 N m range) and needs 301: 200 of `max`
  // (10 ms) over 2 s, and each of the 7 restarts (load steps, law joints) grows from
  // `initial` (10 us) to `max` in some 10 doublings.
  EXPECT_LT(steps, 1000u) << "not half the fixed grid's steps";
  EXPECT_GT(steps, 250u) << "fewer steps than the restarts after the events take: the controller did not refine";
  EXPECT_EQ(s["adaptive_step"]["steps"].get<std::uint64_t>(), steps);
  EXPECT_NEAR(s["adaptive_step"]["shortest_s"].get<double>(), 10e-6, 1e-9) << "every restart begins at `initial`";
  // Under 1 % as the issue asks, and near what the tolerance asks: a few percent over 0.41 %
  // where the estimate lags, not the 2 - 3x of a controller that overshoots.
  EXPECT_LT(s["signals"]["cam.shaft_torque"]["max_rel_error"].get<double>(), 0.006);
  EXPECT_EQ(s["signals"]["follower.contact_force"]["max_abs_error"].get<double>(), 0.0) << "a Gauss-Seidel edge stays exact";
  EXPECT_FALSE(s["adaptive_step"].contains("suggested_scales")) << "the scene writes its scales";
}

TEST_F(Launch, TwoRunsOfASceneGiveBitIdenticalOutputs) {
  ASSERT_EQ(run(launch_args("a"), log("a")).exit_code, 0);
  ASSERT_EQ(run(launch_args("b"), log("b")).exit_code, 0);
  for (const char* node : {"cam", "follower"}) {
    const std::string name = std::string(node) + ".outputs.bin";
    const std::string first = slurp((run_folder("a") / name).string());
    const std::string second = slurp((run_folder("b") / name).string());
    EXPECT_GT(first.size(), 2000u * 8u);
    EXPECT_TRUE(first == second) << name << " differs between two runs";
  }
}

TEST_F(Launch, TwoScenesAtTheSameTimeDoNotSeeEachOther) {
  pid_t slow = spawn(launch_args("slow"), log("slow"));
  pid_t fast = spawn(launch_args("fast", {"--set", "cam.speed=60 rpm"}), log("fast"));
  CommandResult a = wait_for(slow, log("slow"), 120), b = wait_for(fast, log("fast"), 120);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  json s = summary("slow"), f = summary("fast");
  EXPECT_NE(s["domain_id"], f["domain_id"]);
  // Each matches its own reference exactly, so neither consumed the other's samples.
  EXPECT_EQ(s["signals"]["follower.contact_force"]["max_abs_error"].get<double>(), 0.0);
  EXPECT_EQ(f["signals"]["follower.contact_force"]["max_abs_error"].get<double>(), 0.0);
  // And they did compute different things: inertia scales with the speed squared.
  EXPECT_NE(s["report"][1]["value"].get<double>(), f["report"][1]["value"].get<double>());
}

pid_t node_pid(const fs::path& runs, const std::string& node) {
  auto pids = processes_mentioning("--node " + node + " --run-id");
  for (pid_t p : pids)
    if (slurp("/proc/" + std::to_string(p) + "/cmdline").find(runs.string()) != std::string::npos) return p;
  return -1;
}

TEST_F(Launch, ANodeKilledMidRunStopsTheRunAndIsNamed) {
  pid_t launcher = spawn(launch_args("k", {"--end", "600 s"}), log("k"));
  ASSERT_TRUE(wait_for_output_bytes("k", "follower", 10000, 120));
  pid_t follower = node_pid(dir_ / "k", "follower");
  ASSERT_GT(follower, 0);
  ::kill(follower, SIGKILL);
  // The exit is seen at once; stopping the cam takes < 2 s grace (60 s: a guard against a
  // hang, not a measurement).
  CommandResult r = wait_for(launcher, log("k"), 60);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("node 'follower' killed by signal 9"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("last step"), std::string::npos) << r.output;
  json s = json::parse(slurp((run_folder("k") / "summary.json").string()));
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["failure"]["node"], "follower");
  EXPECT_GT(s["failure"]["last_step"].get<long>(), 0);
}

TEST_F(Launch, AHungNodeIsDetectedAndEverythingStops) {
  pid_t launcher = spawn(launch_args("h", {"--end", "600 s", "--set", "hang_timeout=1 s"}), log("h"));
  ASSERT_TRUE(wait_for_output_bytes("h", "cam", 10000, 120));
  pid_t cam = node_pid(dir_ / "h", "cam");
  ASSERT_GT(cam, 0);
  ::kill(cam, SIGSTOP);  // alive but silent: only the missing heartbeat tells
  CommandResult r = wait_for(launcher, log("h"), 60);  // a guard against a hang
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("node 'cam' hung"), std::string::npos) << r.output;
  // The step it stopped at is named, once.
  const auto first = r.output.find("(last step ");
  EXPECT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("(last step ", first + 1), std::string::npos) << r.output;
}

TEST_F(Launch, CtrlCStopsEveryProcessCleanly) {
  pid_t launcher = spawn(launch_args("c", {"--end", "600 s"}), log("c"));
  ASSERT_TRUE(wait_for_output_bytes("c", "follower", 10000, 120));
  ::kill(launcher, SIGINT);
  CommandResult r = wait_for(launcher, log("c"), 60);  // a guard against a hang
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 130) << r.output;
}

// Launcher loss (docs/faults.md): the nodes stop with it, and the run folder keeps what was
// written: a summary marked incomplete, every log, output logs readable up to the last
// whole row, a recording that `mechsim record --recover` completes.
TEST_F(Launch, AKilledLauncherLeavesAReadableRunFolderAndNoProcess) {
  pid_t launcher = spawn(launch_args("k", {"--end", "600 s", "--set", "record=true"}), log("k"));
  // Both nodes stepping, with rows on disk (the checks below read them back).
  ASSERT_TRUE(wait_for_output_bytes("k", "follower", 10000, 120));
  ASSERT_TRUE(wait_for_output_bytes("k", "cam", 10000, 120));
  ::kill(launcher, SIGKILL);
  wait_for(launcher, log("k"), 10);
  for (int i = 0; i < 600 && !processes_mentioning(dir_.string()).empty(); ++i)  // up to 30 s: a guard
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(processes_mentioning(dir_.string()).empty()) << "the nodes outlived their launcher";
  const fs::path folder = run_folder("k");
  const json s = json::parse(slurp((folder / "summary.json").string()));
  EXPECT_EQ(s["status"], "incomplete");
  EXPECT_NE(s["reason"].get<std::string>().find("record --recover"), std::string::npos);
  for (const char* node : {"cam", "follower"}) {
    EXPECT_TRUE(fs::exists(folder / (std::string(node) + ".log"))) << node;
    const cosim::OutputLog out = cosim::read_output_log((folder / (std::string(node) + ".outputs.bin")).string());
    EXPECT_GT(out.rows(), 10u) << node << ": the steps computed before the kill";
  }
  CommandResult fixed = run({kMechsim, "record", "--recover", (folder / "recording.mcap").string(), "-o",
                             (dir_ / "recovered.mcap").string()},
                            log("recover"), 60);
  EXPECT_EQ(fixed.exit_code, 0) << fixed.output;
  EXPECT_TRUE(fs::exists(dir_ / "recovered.mcap"));
}

TEST_F(Launch, ABadSceneIsRefusedBeforeAnyProcessStarts) {
  std::string text = slurp(kCamPress);
  text.replace(text.find("mass: 25 kg"), 11, "mass: -25 kg");
  const std::string bad = (dir_ / "bad.yaml").string();
  std::ofstream(bad) << text;
  CommandResult r = run({kMechsim, "launch", bad, "--runs-dir", (dir_ / "runs").string()}, log("bad"), 30);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(bad + ": participants.follower.params.mass"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "runs")) << "a refused scene must not create a run folder";
  // Overrides get the same validation.
  CommandResult o = run({kMechsim, "launch", kCamPress, "--step", "-1 ms", "--runs-dir", (dir_ / "runs").string()},
                        log("override"), 30);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("time.step"), std::string::npos) << o.output;
  CommandResult c = run({kMechsim, "check", bad}, log("check"), 30);
  EXPECT_EQ(c.exit_code, 2);
}

// `mechsim check` names the angles an adaptive step lands on where the shaft's speed varies
// (the press line's cam is driven through the CVT): they have no time before the run.
TEST(Cli, CheckNamesTheAnglesPredictedDuringTheRun) {
  const std::string log = (fs::temp_directory_path() / ("mechsim-check-" + std::to_string(::getpid()))).string();
  CommandResult c = run({kMechsim, "check", scene_path("press_line.yaml"), "--set", "time.step=adaptive"}, log, 30);
  EXPECT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("steps land where cam's angle reaches 0, 150, 180, 330 deg"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("steps land where follower's input angle reaches 90, 150 deg"), std::string::npos) << c.output;
  CommandResult fixed = run({kMechsim, "check", scene_path("press_line.yaml")}, log, 30);
  EXPECT_EQ(fixed.output.find("steps land where"), std::string::npos) << "a fixed grid does not predict angles";
  fs::remove(log);
}

// Under an adaptive step `mechsim check` says what the nodes' solvers will run at (from the
// tolerance, or written and too loose) and where a sampled block's ticks bound the step.
TEST(Cli, CheckNamesTheNodeTolerancesAndTheSampleTicksOfAnAdaptiveStep) {
  const std::string log = (fs::temp_directory_path() / ("mechsim-check-rtol-" + std::to_string(::getpid()))).string();
  CommandResult c = run({kMechsim, "check", scene_path("nc_slide_loop_1ms.yaml"), "--set", "time.step=adaptive", "--set",
                         "time.tolerance=1e-4", "--set", "participants.slide.solver.rtol=1e-6"},
                        log, 30);
  EXPECT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("steps land on servo's sample instants, every 0.001 s"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("rtol 1e-08, atol 1e-11 (from the adaptive tolerance"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("rtol 1e-06, atol 1e-09 (written; looser than tolerance x 1e-4"), std::string::npos) << c.output;
  CommandResult fixed = run({kMechsim, "check", scene_path("nc_slide_loop_1ms.yaml")}, log, 30);
  EXPECT_EQ(fixed.output.find("sample instants"), std::string::npos) << fixed.output;
  EXPECT_EQ(fixed.output.find("rtol"), std::string::npos) << fixed.output;
  fs::remove(log);
}

// `mechsim check` says which process group each participant will run in: the one it names,
// or the one `processes:` packs it into (docs/scenes.md).
TEST(Cli, CheckNamesEachParticipantsProcessGroup) {
  const std::string log = (fs::temp_directory_path() / ("mechsim-check-groups-" + std::to_string(::getpid()))).string();
  CommandResult c = run({kMechsim, "check", scene_path("nc_slide_loop.yaml"), "--set", "processes=1", "--set",
                         "participants.slide.process=axis"},
                        log, 30);
  EXPECT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("in process group axis\n"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("in process group auto_cyclone_1 (processes: 1 per vendor)"), std::string::npos) << c.output;
  // The default (processes: auto) on one host: one process for the vendor's participants.
  CommandResult automatic = run({kMechsim, "check", scene_path("nc_slide_loop.yaml")}, log, 30);
  EXPECT_NE(automatic.output.find("in process group auto_cyclone_1 (processes: auto)"), std::string::npos) << automatic.output;
  CommandResult apart = run({kMechsim, "check", scene_path("nc_slide_loop.yaml"), "--set", "processes=per_participant"}, log, 30);
  EXPECT_EQ(apart.output.find("process group"), std::string::npos) << "a process per participant, as asked";
  fs::remove(log);
}

// A scene written for an analysis (its design: section) that is not a time run says which
// command it is for, from `check` and from `launch`, before anything starts (exit 2).
TEST(Cli, AnAnalysisSceneNamesItsCommandWhenLaunched) {
  const std::string log = (fs::temp_directory_path() / ("mechsim-analysis-" + std::to_string(::getpid()))).string();
  for (const char* cmd : {"check", "launch"}) {
    CommandResult c = run({kMechsim, cmd, scene_path("cvt_map.yaml")}, log, 30);
    EXPECT_EQ(c.exit_code, 2) << cmd << ": " << c.output;
    EXPECT_NE(c.output.find("participants.cvt.params.drive: missing key"), std::string::npos) << cmd << ": " << c.output;
    EXPECT_NE(c.output.find("cvt_map.yaml is a scene for `mechsim cvt-map"), std::string::npos) << cmd << ": " << c.output;
  }
  // A time scene with an error says nothing about analyses.
  CommandResult plain = run({kMechsim, "check", scene_path("press_line.yaml"), "--set", "participants.cvt.params.drive.type=rocket"}, log, 30);
  EXPECT_EQ(plain.exit_code, 2) << plain.output;
  EXPECT_EQ(plain.output.find("is a scene for"), std::string::npos) << plain.output;
  fs::remove(log);
}

TEST(Cli, VersionAndHelpAnswer) {
  const std::string log = (fs::temp_directory_path() / ("mechsim-cli-" + std::to_string(::getpid()))).string();
  CommandResult v = run({kMechsim, "--version"}, log, 10);
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.output.find("mechsim "), std::string::npos);
  for (const char* cmd : {"launch", "reference", "check"}) {
    CommandResult h = run({kMechsim, cmd, "--help"}, log, 10);
    EXPECT_EQ(h.exit_code, 0) << cmd;
    EXPECT_NE(h.output.find("--set"), std::string::npos) << cmd;
  }
  fs::remove(log);
}

}  // namespace
}  // namespace mechsim::testing
