// Restart with rollback (docs/faults.md): nodes SIGKILLed at random steps are restarted by
// the launcher, every node rolls back to the newest checkpoint they all hold, and the run
// ends with exit 0 and node output files byte-identical to an undisturbed run's. Also a
// kill while a checkpoint is being written, and the restart limit. Label `faults`.
//
// The kill steps come from a seeded generator; the seed is printed, and
// MECHSIM_TEST_SEED=<seed> repeats a run's choice.
#include <signal.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// Rows (steps) in a node's output log so far: what the node has written out (its stdio
// buffer may hold a few more; a checkpoint flushes it).
long rows_written(const fs::path& run, const std::string& node) {
  const fs::path path = run / (node + ".outputs.bin");
  std::ifstream in(path, std::ios::binary);
  std::string magic, names;
  if (!std::getline(in, magic) || !std::getline(in, names)) return -1;
  const long columns = static_cast<long>(std::count(names.begin(), names.end(), ',')) + 1;
  std::error_code ec;
  const auto size = static_cast<long>(fs::file_size(path, ec));
  if (ec) return -1;
  return (size - static_cast<long>(magic.size() + names.size() + 2)) / (columns * 8);
}

// The pid of the running process of `node` in the runs folder `runs` (-1: none now).
pid_t node_pid(const fs::path& runs, const std::string& node) {
  for (int attempt = 0; attempt < 3; ++attempt) {
    try {
      for (pid_t p : processes_mentioning("--node " + node + " --run-id"))
        if (slurp("/proc/" + std::to_string(p) + "/cmdline").find(runs.string()) != std::string::npos) return p;
      return -1;
    } catch (const std::exception&) {
      // a process that ended while its /proc entry was read: look again
    }
  }
  return -1;
}

// The pid of `node`'s process once its output log holds more than `rows` rows (-1 when
// that does not happen within 60 s).
pid_t pid_once_past(const fs::path& runs, const fs::path& run, const std::string& node, long rows) {
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < until) {
    const pid_t pid = node_pid(runs, node);
    if (pid > 0 && rows_written(run, node) > rows) return pid;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return -1;
}

// Waits until the node's log says it resumed `times` times: the run goes on after a restart.
bool wait_resumed(const fs::path& run, const std::string& node, int times) {
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < until) {
    const std::string text = slurp((run / (node + ".log")).string());
    int found = 0;
    for (auto at = text.find("resumed: from step"); at != std::string::npos; at = text.find("resumed: from step", at + 1)) ++found;
    if (found >= times) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

std::uint64_t seed() {
  if (const char* s = std::getenv("MECHSIM_TEST_SEED")) return std::strtoull(s, nullptr, 10);
  return std::random_device{}();
}

class Restart : public RunFolderTest {
 protected:
  // The run folder once it exists (the launcher creates it before the nodes).
  // nc_slide_loop_1ms for 1 s, undisturbed ("plain", waited for), then again ("killed",
  // returned running) with restart on, a checkpoint every 100 steps and `more` arguments
  // (a participant's `testing:` seam among them).
  pid_t run_plain_then_start_killable(const std::vector<std::string>& more) {
    const std::vector<std::string> extra{"--end", "1 s"};
    CommandResult plain = run(launch_args_a_process_each(scene_path("nc_slide_loop_1ms.yaml"), "plain", extra), log("plain"), 120);
    EXPECT_EQ(plain.exit_code, 0) << plain.output;
    std::vector<std::string> args = extra;
    args.insert(args.end(), {"--set", "faults.restart=on_failure", "--set", "faults.checkpoint_every=100"});
    args.insert(args.end(), more.begin(), more.end());
    return spawn(launch_args_a_process_each(scene_path("nc_slide_loop_1ms.yaml"), "killed", args), log("killed"));
  }
  // Every node's output and events files of two runs, byte for byte.
  void expect_identical_outputs(const fs::path& a, const fs::path& b, const std::vector<std::string>& nodes) {
    for (const auto& n : nodes)
      for (const std::string suffix : {".outputs.bin", ".events.jsonl"}) {
        const std::string fa = slurp((a / (n + suffix)).string()), fb = slurp((b / (n + suffix)).string());
        EXPECT_FALSE(suffix == ".outputs.bin" && fa.empty()) << n << suffix << " is empty";
        EXPECT_TRUE(fa == fb) << n << suffix << " differs from the undisturbed run (" << fa.size() << " vs " << fb.size() << " bytes)";
      }
  }

  // Launches `scene` undisturbed and with restart on, kills a random node (of `victims`, by
  // default of `nodes`) at `kills` random steps of the second run, and checks that it
  // completes byte-identical.
  void kill_at_random_steps(const std::string& scene, const std::vector<std::string>& nodes, long steps,
                            std::vector<std::string> extra, int kills, std::vector<std::string> victims = {}) {
    if (victims.empty()) victims = nodes;
    const std::uint64_t s = seed();
    std::cout << "restart test seed " << s << " (MECHSIM_TEST_SEED=" << s << " repeats it)" << std::endl;
    RecordProperty("seed", std::to_string(s));
    std::mt19937_64 rng(s);
    const long every = 50;
    // Targets between the second checkpoint and 80 % of the run, at least 100 steps apart.
    std::set<long> targets;
    std::uniform_int_distribution<long> step_dist(2 * every, steps * 8 / 10);
    while (static_cast<int>(targets.size()) < kills) {
      const long k = step_dist(rng);
      bool apart = true;
      for (long t : targets) apart = apart && std::labs(t - k) >= 100;
      if (apart) targets.insert(k);
    }
    std::uniform_int_distribution<std::size_t> node_dist(0, victims.size() - 1);

    CommandResult plain = run(launch_args_a_process_each(scene_path(scene), "plain", extra), log("plain"), 180);
    ASSERT_EQ(plain.exit_code, 0) << plain.output;

    std::vector<std::string> args = extra;
    args.insert(args.end(), {"--set", "faults.restart=on_failure", "--set", "faults.checkpoint_every=" + std::to_string(every),
                             "--set", "faults.restart_limit=" + std::to_string(kills)});
    const pid_t launcher = spawn(launch_args_a_process_each(scene_path(scene), "killed", args), log("killed"));
    StopOnExit stop{launcher};
    const fs::path run = wait_for_run_folder("killed");
    ASSERT_FALSE(run.empty());
    std::vector<std::string> killed;
    std::map<std::string, int> restarts_of;
    for (long target : targets) {
      const std::string node = victims[node_dist(rng)];
      const pid_t pid = pid_once_past(dir_ / "killed", run, node, target);
      ASSERT_GT(pid, 0) << "node " << node << " did not reach step " << target << "\n" << slurp(log("killed"));
      // The log grows in whole buffers (and at each checkpoint): a random pause puts the
      // kill anywhere between two checkpoints.
      std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 40'000)(rng)));
      std::cout << "kill " << node << " (pid " << pid << ") at step ~" << rows_written(run, node) - 1 << " (target " << target << ")"
                << std::endl;
      ::kill(pid, SIGKILL);
      killed.push_back(node);
      // The next kill is of the resumed run.
      ASSERT_TRUE(wait_resumed(run, node, ++restarts_of[node])) << slurp(log("killed"));
    }
    CommandResult r = wait_for(launcher, log("killed"), 180);
    stop.pid = -1;
    ASSERT_FALSE(r.timed_out) << r.output;
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json summary = json::parse(slurp((run / "summary.json").string()));
    ASSERT_TRUE(summary.contains("restart")) << summary.dump(1);
    const json& restarts = summary["restart"]["restarts"];
    ASSERT_EQ(restarts.size(), static_cast<std::size_t>(kills)) << restarts.dump(1);
    for (std::size_t i = 0; i < restarts.size(); ++i) {
      const json& x = restarts[i];
      EXPECT_EQ(x["node"], killed[i]);
      EXPECT_EQ(x["exit"], "killed by signal 9 (Killed)");
      // Back to a checkpoint at or before the step it died at, a multiple of the interval.
      EXPECT_EQ(x["rollback_step"].get<long>() % every, 0);
      EXPECT_LE(x["rollback_step"].get<long>(), x["last_step"].get<long>() + 1);
      EXPECT_GT(x["stepping_s"].get<double>(), x["detected_s"].get<double>());
      std::cout << "restart " << i + 1 << ": " << x.dump() << std::endl;
    }
    expect_identical_outputs(run_folder("plain"), run, nodes);
  }
};

TEST_F(Restart, NcSlideLoop1msSurvivesFiveKillsByteIdentical) {
  kill_at_random_steps("nc_slide_loop_1ms.yaml", {"servo", "tacho", "slide"}, 3000, {"--end", "3 s"}, 5);
}

TEST_F(Restart, PressLineSurvivesFiveKillsByteIdentical) {
  kill_at_random_steps("press_line.yaml", {"cvt", "cam", "follower"}, 2000, {}, 5);
}

// The servo amplifier played by its test FMU (docs/fmi.md), which declares that it can get,
// set and serialize its state: its checkpoints hold the FMU's serialized state. Killed, the
// co-simulation FMU's node comes back in a new process that deserializes it; with the
// model-exchange FMU the tacho is killed and the live FMU node rolls back in its process.
// Either way the run ends byte-identical to an undisturbed run with the same FMU.
TEST_F(Restart, AnFmuServoRollsBackByteIdentical) {
  const std::string fmus = MECHSIM_TEST_FMU_DIR;
  const auto with_fmu = [&](const std::string& stem, const std::string& interface) {
    return std::vector<std::string>{"--end", "1 s", "--set", "participants.servo.fmu.file=" + fmus + "/" + stem + ".fmu",
                                    "--set", "participants.servo.fmu.interface=" + interface,
                                    "--set", "participants.servo.fmu.parameters.step_distance=0.1 mm"};
  };
  kill_at_random_steps("nc_slide_loop_1ms.yaml", {"servo", "tacho", "slide"}, 1000,
                       with_fmu("servo_amplifier_fmi2_cs", "co-simulation"), 2, {"servo"});
  ASSERT_FALSE(HasFailure());
  fs::remove_all(dir_ / "plain");
  fs::remove_all(dir_ / "killed");
  kill_at_random_steps("nc_slide_loop_1ms.yaml", {"servo", "tacho", "slide"}, 1000,
                       with_fmu("servo_amplifier_fmi3_me", "model-exchange"), 2, {"tacho"});
}

// A node killed while it writes a checkpoint: its previous checkpoint is whole, and the run
// rolls back to the newest one every node holds completely.
TEST_F(Restart, AKillDuringACheckpointRollsBackToThePreviousOne) {
  // Recorded too: the recording keeps the first copy of each step (docs/faults.md, 'Recording').
  const pid_t launcher = run_plain_then_start_killable({"--set", "record=true", "--set", "participants.slide.testing.checkpoint_pause_step=300",
                                                       "--set", "participants.slide.testing.checkpoint_pause=3 s"});
  StopOnExit stop{launcher};
  ASSERT_FALSE(HasFailure());
  const fs::path run = wait_for_run_folder("killed");
  ASSERT_FALSE(run.empty());
  ASSERT_TRUE(wait_for_path(run / "checkpoints" / "slide.300.ckpt.tmp", 60)) << slurp(log("killed"));
  const pid_t slide = node_pid(dir_ / "killed", "slide");
  ASSERT_GT(slide, 0);
  ::kill(slide, SIGKILL);
  CommandResult r = wait_for(launcher, log("killed"), 120);
  stop.pid = -1;
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json summary = json::parse(slurp((run / "summary.json").string()));
  const json& restarts = summary["restart"]["restarts"];
  ASSERT_EQ(restarts.size(), 1u) << summary.dump(1);
  EXPECT_EQ(restarts[0]["node"], "slide");
  EXPECT_EQ(restarts[0]["rollback_step"], 200) << "the half-written checkpoint of step 300 must not be used";
  ASSERT_TRUE(summary.contains("recording")) << summary.dump(1);
  EXPECT_TRUE(summary["recording"]["complete"].get<bool>()) << summary["recording"].dump(1);
  bool repeats = false;
  for (const auto& t : summary["recording"]["topics"]) repeats = repeats || t.contains("repeated_after_rollback");
  EXPECT_TRUE(repeats) << "the steps after the checkpoint were sent twice; the recording counts the second copies";
  expect_identical_outputs(run_folder("plain"), run, {"servo", "tacho", "slide"});
}

// The restarted node's writers and readers are new to its partners, and each side of DDS
// discovery completes on its own: a sample written at the resume may reach nobody (seen in
// CI: the restarted slide never got tacho's prediction and the run stalled). Made certain
// here: tacho leaves out its first writes after the resume; the nodes that then wait send
// what they wrote since the rollback again, and the run completes byte-identical.
TEST_F(Restart, SamplesLostAtTheResumeAreSentAgain) {
  const pid_t launcher = run_plain_then_start_killable({"--set", "participants.tacho.testing.lose_writes_after_resume=true"});
  StopOnExit stop{launcher};
  ASSERT_FALSE(HasFailure());
  const fs::path run = wait_for_run_folder("killed");
  ASSERT_FALSE(run.empty());
  const pid_t pid = pid_once_past(dir_ / "killed", run, "slide", 300);
  ASSERT_GT(pid, 0) << slurp(log("killed"));
  ::kill(pid, SIGKILL);
  CommandResult r = wait_for(launcher, log("killed"), 120);
  stop.pid = -1;
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(slurp((run / "tacho.log").string()).find("sent again"), std::string::npos) << slurp((run / "tacho.log").string());
  expect_identical_outputs(run_folder("plain"), run, {"servo", "tacho", "slide"});
}

// More deaths of one participant than faults.restart_limit: the run stops as without
// restart (exit 1, every process stopped), naming the node and its restarts.
TEST_F(Restart, MoreDeathsThanTheLimitStopTheRunCleanly) {
  const pid_t launcher = spawn(launch_args_a_process_each(scene_path("nc_slide_loop_1ms.yaml"), "limit",
                                           {"--end", "600 s", "--set", "faults.restart=on_failure", "--set",
                                            "faults.checkpoint_every=50", "--set", "faults.restart_limit=1"}),
                               log("limit"));
  StopOnExit stop{launcher};
  const fs::path run = wait_for_run_folder("limit");
  ASSERT_FALSE(run.empty());
  for (int kill = 0; kill < 2; ++kill) {
    const pid_t pid = pid_once_past(dir_ / "limit", run, "tacho", 300);
    ASSERT_GT(pid, 0) << slurp(log("limit"));
    ::kill(pid, SIGKILL);
    if (kill == 0) {
      ASSERT_TRUE(wait_resumed(run, "tacho", 1)) << slurp(log("limit"));
    }
  }
  CommandResult r = wait_for(launcher, log("limit"), 30);
  stop.pid = -1;
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("node 'tacho' killed by signal 9 (Killed) after 1 restart(s): faults.restart_limit 1 reached"), std::string::npos)
      << r.output;
  const json summary = json::parse(slurp((run / "summary.json").string()));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_EQ(summary["failure"]["node"], "tacho");
  EXPECT_EQ(summary["restart"]["restarts"].size(), 1u);
}

}  // namespace
}  // namespace mechsim::testing
