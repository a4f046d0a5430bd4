// Multi-host runs on the namespace test bed (tools/netns-hosts.sh, docs/hosts.md): every
// participant on a host of its own, the launcher on host 1 (where participant 1 runs as
// its child) and a `mechsim agent` on each further host, multicast dropped on every host.
//  - nc_slide_loop, press_line and cam_press on Cyclone, Fast DDS and mixed give node
//    outputs byte-identical to the single-host run, and the launcher's run folder holds the
//    same files;
//  - a launcher that is killed leaves nothing running on any host (the agents' heartbeat
//    timeout), a missing agent is named, and stopped agents leave no process behind.
// Needs root (namespaces, veth pairs, iptables): without it every test prints as skipped
// (ctest SKIP_REGULAR_EXPRESSION). Label `hosts`, run by .ci/run.
#include "host_bed.h"

namespace mechsim::testing {
namespace {

using nlohmann::json;

struct Case {
  const char* scene;
  std::vector<std::string> participants;  // in scene order: participant i goes to host i
  const char* layout;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.scene << " on " << c.layout; }

class AcrossHosts : public HostBed, public ::testing::WithParamInterface<Case> {};

TEST_P(AcrossHosts, NodeOutputsAreByteIdenticalToTheSingleHostRun) {
  const Case& c = GetParam();
  const std::string layout = c.layout;
  if ((layout != "fastdds" && !compiled_in("cyclone")) || (layout != "cyclone" && !compiled_in("fastdds")))
    GTEST_SKIP() << "layout '" << layout << "' needs a DDS vendor this build left out";
  start_agents(static_cast<int>(c.participants.size()));

  // The single-host run, on this machine's loopback (a domain of its own), with a process per
  // participant as across hosts, so that both run folders hold the same files.
  const fs::path single = dir_ / "single";
  const CommandResult one = run({kMechsim, "launch", kScenes + c.scene, "--runs-dir", single.string(), "--no-plot", "--no-progress",
                                 "--dds", layout, "--set", "processes=per_participant"},
                                single.string() + ".log", 240);
  ASSERT_EQ(one.exit_code, 0) << one.output;

  const fs::path multi = dir_ / "multi";
  const CommandResult across = launch_across(c.scene, c.participants, layout, multi);
  ASSERT_EQ(across.exit_code, 0) << across.output << "\nagent logs in " << dir_;
  EXPECT_NE(across.output.find("multi-host run: launcher on h1 (10.77.0.1)"), std::string::npos) << across.output;

  const fs::path a = only_run_folder(single), b = only_run_folder(multi);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  const json summary = json::parse(slurp((b / "summary.json").string()));
  for (std::size_t i = 0; i < c.participants.size(); ++i) {
    const std::string& p = c.participants[i];
    EXPECT_EQ(summary["nodes"][p]["host"], "h" + std::to_string(i + 1)) << p;
    EXPECT_EQ(summary["nodes"][p]["exit"].get<std::string>().rfind("exit code 0", 0), 0u) << summary["nodes"][p].dump();
    const std::string first = slurp((a / (p + ".outputs.bin")).string());
    const std::string second = slurp((b / (p + ".outputs.bin")).string());
    EXPECT_GT(first.size(), 1000u) << p;
    EXPECT_TRUE(first == second) << p << ".outputs.bin differs between the single-host and the multi-host run (" << first.size()
                                 << " vs " << second.size() << " bytes)";
  }
  // The run folder is complete: the files of the single-host run, whoever wrote them.
  const auto files_single = file_names(a), files_multi = file_names(b);
  for (const auto& f : files_single) EXPECT_TRUE(files_multi.count(f)) << f << " is missing from the multi-host run folder " << b;
  EXPECT_TRUE(summary["hosts"]["hand_back_problems"].empty()) << summary["hosts"].dump();
  EXPECT_EQ(summary["hosts"]["agents"].size(), c.participants.size() - 1) << summary["hosts"].dump();
}

std::string case_name(const ::testing::TestParamInfo<Case>& i) {
  std::string s = std::string(i.param.scene) + "_" + i.param.layout;
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

const std::vector<std::string> kNc{"servo", "tacho", "slide"};
const std::vector<std::string> kPress{"cvt", "cam", "follower"};
const std::vector<std::string> kCam{"cam", "follower"};

INSTANTIATE_TEST_SUITE_P(Scenes, AcrossHosts,
                         ::testing::Values(Case{"nc_slide_loop.yaml", kNc, "cyclone"}, Case{"nc_slide_loop.yaml", kNc, "fastdds"},
                                           Case{"nc_slide_loop.yaml", kNc, "mixed"}, Case{"press_line.yaml", kPress, "cyclone"},
                                           Case{"press_line.yaml", kPress, "fastdds"}, Case{"press_line.yaml", kPress, "mixed"},
                                           Case{"cam_press.yaml", kCam, "cyclone"}, Case{"cam_press.yaml", kCam, "fastdds"},
                                           Case{"cam_press.yaml", kCam, "mixed"}),
                         case_name);

TEST_F(HostBed, AKilledLauncherLeavesNothingRunningOnAnyHost) {
  start_agents(3, 2.0);
  const fs::path runs = dir_ / "killed";
  // A long run (10 s simulated: minutes of wall time), killed once every node computes.
  std::vector<std::string> argv{ip_command(), "netns", "exec", ns(1), kMechsim, "launch", kScenes + "nc_slide_loop.yaml",
                                "--runs-dir", runs.string(), "--no-plot", "--no-progress", "--end", "10 s",
                                "--set", "dds.domain=" + std::to_string(kDomain)};
  for (int i = 0; i < 3; ++i) {
    const auto keys = host_args(i + 1);
    argv.insert(argv.end(), keys.begin(), keys.end());
    argv.insert(argv.end(), {"--set", "participants." + kNc[static_cast<std::size_t>(i)] + ".host=h" + std::to_string(i + 1)});
  }
  const pid_t launcher = spawn(argv, runs.string() + ".log");
  // Running: the remote nodes' processes exist on hosts 2 and 3 (the agent plus its node).
  bool running = false;
  for (int i = 0; i < 300 && !running; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    running = pids_in(ns(2)).size() >= 2 && pids_in(ns(3)).size() >= 2 && slurp(runs.string() + ".log").find("waiting for the agents") != std::string::npos;
  }
  ASSERT_TRUE(running) << slurp(runs.string() + ".log");
  // Stepping: the amplifier beside the launcher has written 16 KiB of rows (120 s: a guard).
  for (int i = 0; i < 6000 && output_bytes(runs, "servo") < 16384; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(output_bytes(runs, "servo"), 16384u) << slurp(runs.string() + ".log");
  ::kill(launcher, SIGKILL);
  wait_for(launcher, "/dev/null", 5);
  // Host 1: its node dies with the launcher (PR_SET_PDEATHSIG); hosts 2, 3: their nodes end
  // on the partition watchdog (2 s) or are stopped by their agent after its heartbeat timeout.
  std::string left;
  EXPECT_TRUE(only_one_process_left_on_hosts_2_and_3(left)) << left << " (agents count 1)";
  // The agent dropped the run after its heartbeat timeout (its node may have ended before,
  // on its own partition watchdog: its partner on host 1 died with the launcher).
  for (int i = 0; i < 50 && slurp((dir_ / "agent2.log").string()).find("forgotten") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_NE(slurp((dir_ / "agent2.log").string()).find("forgotten"), std::string::npos) << slurp((dir_ / "agent2.log").string());
}

TEST_F(HostBed, AMissingAgentIsNamedAndNothingStarts) {
  start_agents(2);  // none on host 3
  const fs::path runs = dir_ / "missing";
  const CommandResult r3 = run({ip_command(), "netns", "exec", ns(1), kMechsim, "launch", kScenes + "cam_press.yaml", "--runs-dir",
                                runs.string(), "--no-plot", "--no-progress", "--set", "dds.domain=" + std::to_string(kDomain), "--set",
                                "hosts.h1.address=" + address(1), "--set", "hosts.h3.address=" + address(3), "--set",
                                "hosts.h3.control=dds_agent", "--set", "participants.follower.host=h3"},
                               runs.string() + "-3.log", 120);
  EXPECT_EQ(r3.exit_code, 1) << r3.output;
  EXPECT_NE(r3.output.find("no mechsim agent answered from 10.77.0.3 on domain 7"), std::string::npos) << r3.output;
  EXPECT_TRUE(pids_in(ns(1)).empty()) << "the launcher left processes on host 1";
}

// docs/hosts.md's namespace example as written: agents without --work-dir, all on this
// machine's one filesystem. Each takes a folder of its own (/var/tmp/mechsim-agent/
// <address>-domain<D>), so neither reads the other's DDS configuration (which names its
// host's address: a node reading the other's fails at once, "does not match an available
// interface"), and the run is byte-identical to the single-host one. A second agent on a
// folder in use is refused, naming it.
TEST_F(HostBed, AgentsWithDefaultWorkFoldersOnOneFilesystemKeepTheirFilesApart) {
  start_agents(3, 3.0, /*default_work_dirs=*/true);
  const fs::path single = dir_ / "single";
  const CommandResult one = run({kMechsim, "launch", kScenes + "nc_slide_loop.yaml", "--runs-dir", single.string(), "--no-plot",
                                 "--no-progress", "--dds", "cyclone"},
                                single.string() + ".log", 240);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const fs::path multi = dir_ / "multi";
  const CommandResult across = launch_across("nc_slide_loop.yaml", kNc, "cyclone", multi);
  ASSERT_EQ(across.exit_code, 0) << across.output << "\nagent logs in " << dir_;
  const fs::path a = only_run_folder(single), b = only_run_folder(multi);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  for (const std::string& p : kNc) {
    const std::string first = slurp((a / (p + ".outputs.bin")).string());
    EXPECT_GT(first.size(), 1000u) << p;
    EXPECT_TRUE(first == slurp((b / (p + ".outputs.bin")).string())) << p << ".outputs.bin differs from the single-host run";
  }
  // Each agent's folder and DDS configuration are its own: its address, not the other's.
  for (int h = 2; h <= 3; ++h) {
    const std::string work = "/var/tmp/mechsim-agent/" + address(h) + "-domain" + std::to_string(kDomain);
    const std::string agent_log = slurp((dir_ / ("agent" + std::to_string(h) + ".log")).string());
    EXPECT_NE(agent_log.find("work folder " + work + ","), std::string::npos) << agent_log;
    const std::string other = address(h == 2 ? 3 : 2);
    for (const char* file : {"cyclonedds.xml", "fastdds.xml"}) {
      const std::string config = slurp(work + "/dds/" + file);
      EXPECT_NE(config.find(address(h)), std::string::npos) << work << "/dds/" << file;
      // The peers list holds the launcher's host and this one only (start_agents: --peers host 1).
      EXPECT_EQ(config.find(other), std::string::npos) << work << "/dds/" << file << " names the other agent's address";
    }
  }
  // A second agent for host 2's address and domain would share its default folder: refused.
  const CommandResult second = run({ip_command(), "netns", "exec", ns(2), kMechsim, "agent", "--domain", std::to_string(kDomain),
                                    "--address", address(2), "--peers", address(1), "--allow-unauthenticated", "--exit-after", "5"},
                                   (dir_ / "agent2-second.log").string(), 30);
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_NE(second.output.find("work folder /var/tmp/mechsim-agent/10.77.0.2-domain7 is in use by another mechsim agent (pid "),
            std::string::npos)
      << second.output;
}

}  // namespace
}  // namespace mechsim::testing
