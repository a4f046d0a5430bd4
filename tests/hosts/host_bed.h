// The network-namespace test bed for one test (tools/netns-hosts.sh): kHosts hosts
// mh<pid>-h1..n with addresses 10.77.0.1..n, agents on hosts 2.., the launcher on host 1;
// built in SetUp, removed in TearDown (and by the ctest cleanup fixture `hosts_bed_cleanup`
// should the test process be killed). Shared by hosts_test and faults_test.
#pragma once

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
#include "run_fixture.h"  // kMechsim, run_command.h, expect_identical_node_outputs

namespace mechsim::testing {

namespace fs = std::filesystem;

inline const std::string kScenes = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/";
inline const std::string kBedScript = std::string(MECHSIM_SOURCE_DIR) + "/tools/netns-hosts.sh";
inline constexpr int kDomain = 7;  // inside the bed's namespaces nothing else shares it
inline constexpr int kHosts = 4;

inline std::string ip_command() {
  for (const char* p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"})
    if (::access(p, X_OK) == 0) return p;
  return "";
}

inline bool compiled_in(const std::string& vendor) {
  const auto v = transport::available_vendors();
  return std::find(v.begin(), v.end(), vendor) != v.end();
}

inline int shell(const std::string& command) {
  const int rc = std::system(command.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Pids of the processes inside one namespace.
inline std::vector<pid_t> pids_in(const std::string& ns) {
  std::vector<pid_t> out;
  FILE* f = ::popen((ip_command() + " netns pids " + ns + " 2>/dev/null").c_str(), "r");
  if (!f) return out;
  char line[64];
  while (std::fgets(line, sizeof line, f)) out.push_back(std::atoi(line));
  ::pclose(f);
  return out;
}

inline std::set<std::string> file_names(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) names.insert(e.path().filename().string());
  return names;
}

inline fs::path only_run_folder(const fs::path& runs) {
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
  // Each works in a folder of this bed's, or, with default_work_dirs, in the default one
  // (as docs/hosts.md's example does: all on this machine's one filesystem).
  void start_agents(int last, double heartbeat_timeout_s = 3.0, bool default_work_dirs = false) {
    for (int h = 2; h <= last; ++h) {
      std::vector<std::string> argv{ip_command(), "netns", "exec", ns(h), kMechsim, "agent", "--domain", std::to_string(kDomain),
                                    "--address", address(h), "--peers", address(1),
                                    "--heartbeat-timeout", std::to_string(heartbeat_timeout_s)};
      if (!default_work_dirs) argv.insert(argv.end(), {"--work-dir", (dir_ / ("agent" + std::to_string(h))).string()});
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

  // Every packet arriving at every host dropped with probability p (iptables statistic).
  void drop_randomly(double p, int hosts = kHosts) {
    for (int h = 1; h <= hosts; ++h)
      ASSERT_EQ(shell("ip netns exec " + ns(h) + " iptables -A INPUT -i eth0 -m statistic --mode random --probability " +
                      std::to_string(p) + " -j DROP"),
                0);
  }
  // Host h's interface cut both ways (the other hosts' packets to it vanish), and healed.
  void cut_host(int h) {
    ASSERT_EQ(shell("ip netns exec " + ns(h) + " iptables -I INPUT -i eth0 -j DROP && ip netns exec " + ns(h) +
                    " iptables -I OUTPUT -o eth0 -j DROP"),
              0);
  }
  void heal_host(int h) {
    ASSERT_EQ(shell("ip netns exec " + ns(h) + " iptables -D INPUT -i eth0 -j DROP && ip netns exec " + ns(h) +
                    " iptables -D OUTPUT -o eth0 -j DROP"),
              0);
  }

  std::string prefix_;
  fs::path dir_;
  bool bed_up_ = false;
  std::vector<pid_t> agents_;
};

}  // namespace mechsim::testing
