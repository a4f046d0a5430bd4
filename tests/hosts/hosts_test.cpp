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
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "mechsim/transport/backends.h"
#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kMechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
const std::string kScenes = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/";
const std::string kBedScript = std::string(MECHSIM_SOURCE_DIR) + "/tools/netns-hosts.sh";
constexpr int kDomain = 7;  // inside the bed's namespaces nothing else shares it
constexpr int kHosts = 4;

std::string ip_command() {
  for (const char* p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"})
    if (::access(p, X_OK) == 0) return p;
  return "";
}

bool compiled_in(const std::string& vendor) {
  const auto v = transport::available_vendors();
  return std::find(v.begin(), v.end(), vendor) != v.end();
}

int shell(const std::string& command) {
  const int rc = std::system(command.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Pids of the processes inside one namespace.
std::vector<pid_t> pids_in(const std::string& ns) {
  std::vector<pid_t> out;
  FILE* f = ::popen((ip_command() + " netns pids " + ns + " 2>/dev/null").c_str(), "r");
  if (!f) return out;
  char line[64];
  while (std::fgets(line, sizeof line, f)) out.push_back(std::atoi(line));
  ::pclose(f);
  return out;
}

std::set<std::string> file_names(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) names.insert(e.path().filename().string());
  return names;
}

fs::path only_run_folder(const fs::path& runs) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(runs))
    if (e.is_directory()) found.push_back(e.path());
  return found.size() == 1 ? found[0] : fs::path();
}

// The bed and its agents, for one test: built in SetUp, removed in TearDown (and by the
// ctest cleanup fixture `hosts_bed_cleanup` should this process be killed).
class HostBed : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root: network namespaces, veth pairs and iptables";
    if (ip_command().empty()) GTEST_SKIP() << "needs iproute2 ('ip')";
    prefix_ = "mh" + std::to_string(::getpid());
    dir_ = fs::temp_directory_path() / ("mechsim-hosts-" + prefix_);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ASSERT_EQ(shell("MECHSIM_NETNS_PREFIX=" + prefix_ + " " + kBedScript + " up " + std::to_string(kHosts) + " > " +
                    (dir_ / "bed.log").string() + " 2>&1"),
              0)
        << slurp((dir_ / "bed.log").string());
    bed_up_ = true;
  }

  void TearDown() override {
    if (!bed_up_) return;
    stop_agents();
    EXPECT_EQ(shell("MECHSIM_NETNS_PREFIX=" + prefix_ + " " + kBedScript + " down"), 0);
    FILE* f = ::popen((ip_command() + " netns list").c_str(), "r");
    std::string list;
    char line[256];
    while (f && std::fgets(line, sizeof line, f)) list += line;
    if (f) ::pclose(f);
    EXPECT_EQ(list.find(prefix_ + "-"), std::string::npos) << "namespaces left behind:\n" << list;
    if (!HasFailure()) fs::remove_all(dir_);
  }

  std::string ns(int host) const { return prefix_ + "-h" + std::to_string(host); }
  std::string address(int host) const { return "10.77.0." + std::to_string(host); }

  // An agent on each of hosts 2..last; the one on host 3 speaks Fast DDS itself (when built).
  void start_agents(int last, double heartbeat_timeout_s = 3.0) {
    for (int h = 2; h <= last; ++h) {
      std::vector<std::string> argv{ip_command(), "netns", "exec", ns(h), kMechsim, "agent", "--domain", std::to_string(kDomain),
                                    "--address", address(h), "--peers", address(1),
                                    "--work-dir", (dir_ / ("agent" + std::to_string(h))).string(),
                                    "--heartbeat-timeout", std::to_string(heartbeat_timeout_s)};
      if (h == 3 && compiled_in("fastdds")) argv.insert(argv.end(), {"--dds", "fastdds"});
      agents_.push_back(spawn(argv, (dir_ / ("agent" + std::to_string(h) + ".log")).string()));
    }
  }

  void stop_agents() {
    for (pid_t pid : agents_) ::kill(pid, SIGTERM);
    for (pid_t pid : agents_) {
      const CommandResult r = wait_for(pid, "/dev/null", 10);
      EXPECT_FALSE(r.timed_out) << "an agent did not stop on SIGTERM";
    }
    agents_.clear();
    // A stopped agent leaves nothing running on its host.
    for (int h = 2; h <= kHosts; ++h) EXPECT_TRUE(pids_in(ns(h)).empty()) << "processes left on host " << h;
  }

  // `mechsim launch` on host 1 with participant i on host i.
  CommandResult launch_across(const std::string& scene, const std::vector<std::string>& participants, const std::string& layout,
                              const fs::path& runs, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv{ip_command(), "netns", "exec", ns(1), kMechsim, "launch", kScenes + scene,
                                  "--runs-dir", runs.string(), "--no-plot", "--no-progress", "--set", "dds.domain=" + std::to_string(kDomain)};
    if (!layout.empty()) argv.insert(argv.end(), {"--dds", layout});
    for (std::size_t i = 0; i < participants.size(); ++i) {
      const std::string host = "h" + std::to_string(i + 1);
      argv.insert(argv.end(), {"--set", "hosts." + host + ".address=" + address(static_cast<int>(i) + 1), "--set",
                               "participants." + participants[i] + ".host=" + host});
    }
    argv.insert(argv.end(), extra.begin(), extra.end());
    return run(argv, (runs.string() + ".log"), 240);
  }

  std::string prefix_;
  fs::path dir_;
  bool bed_up_ = false;
  std::vector<pid_t> agents_;
};

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

  // The single-host run, on this machine's loopback (a domain of its own).
  const fs::path single = dir_ / "single";
  const CommandResult one = run({kMechsim, "launch", kScenes + c.scene, "--runs-dir", single.string(), "--no-plot", "--no-progress",
                                 "--dds", layout},
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
  for (int i = 0; i < 3; ++i)
    argv.insert(argv.end(), {"--set", "hosts.h" + std::to_string(i + 1) + ".address=" + address(i + 1), "--set",
                             "participants." + kNc[static_cast<std::size_t>(i)] + ".host=h" + std::to_string(i + 1)});
  const pid_t launcher = spawn(argv, runs.string() + ".log");
  // Running: the remote nodes' processes exist on hosts 2 and 3 (the agent plus its node).
  bool running = false;
  for (int i = 0; i < 300 && !running; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    running = pids_in(ns(2)).size() >= 2 && pids_in(ns(3)).size() >= 2 && slurp(runs.string() + ".log").find("waiting for the agents") != std::string::npos;
  }
  ASSERT_TRUE(running) << slurp(runs.string() + ".log");
  std::this_thread::sleep_for(std::chrono::seconds(2));  // stepping by now
  ::kill(launcher, SIGKILL);
  wait_for(launcher, "/dev/null", 5);
  // Host 1: its node dies with the launcher (PR_SET_PDEATHSIG); hosts 2, 3: their nodes end
  // on the partition watchdog (2 s) or are stopped by their agent after its heartbeat timeout.
  bool clean = false;
  for (int i = 0; i < 100 && !clean; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    clean = pids_in(ns(1)).empty() && pids_in(ns(2)).size() == 1 && pids_in(ns(3)).size() == 1;
  }
  EXPECT_TRUE(clean) << "processes left: host 1 " << pids_in(ns(1)).size() << ", host 2 " << pids_in(ns(2)).size() << ", host 3 "
                     << pids_in(ns(3)).size() << " (agents count 1)";
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
                                "participants.follower.host=h3"},
                               runs.string() + "-3.log", 120);
  EXPECT_EQ(r3.exit_code, 1) << r3.output;
  EXPECT_NE(r3.output.find("no mechsim agent answered from 10.77.0.3 on domain 7"), std::string::npos) << r3.output;
  EXPECT_TRUE(pids_in(ns(1)).empty()) << "the launcher left processes on host 1";
}

}  // namespace
}  // namespace mechsim::testing
