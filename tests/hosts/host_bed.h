// The network-namespace test bed for one test (tools/netns-hosts.sh): kHosts hosts
// mh<pid>-h1..n with addresses 10.77.0.1..n, the launcher on host 1, and on hosts 2.. either
// an sshd (start_sshd: the launcher reaches them over ssh, the default) or a standing DDS
// agent (start_agents: control dds_agent);
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
                                    "--address", address(h), "--peers", address(1), "--allow-unauthenticated",
                                    "--heartbeat-timeout", std::to_string(heartbeat_timeout_s)};
      if (!default_work_dirs) argv.insert(argv.end(), {"--work-dir", (dir_ / ("agent" + std::to_string(h))).string()});
      if (h == 3 && compiled_in("fastdds")) argv.insert(argv.end(), {"--dds", "fastdds"});
      agents_.push_back(spawn(argv, (dir_ / ("agent" + std::to_string(h) + ".log")).string()));
    }
  }

  // An sshd on each of hosts 2..last (`sshd -D -f CONFIG`, listening on the host's address
  // only), with a host key and an authorized key this test made (ssh-keygen -t ed25519), and
  // the client's ssh config the launcher is pointed to (hosts.<h>.ssh_config): that key, a
  // known_hosts with the host key, StrictHostKeyChecking yes. An outsider key is made too,
  // not authorised. Launches (launch_across, host_args) then go over ssh.
  void start_sshd(int last) {
    if (::access("/usr/sbin/sshd", X_OK) != 0 || ::access("/usr/bin/ssh", X_OK) != 0)
      GTEST_SKIP() << "needs OpenSSH (Debian packages openssh-server openssh-client: tools/install-deps.sh --tests)";
    const fs::path ssh = dir_ / "ssh";
    fs::create_directories(ssh);
    fs::permissions(ssh, fs::perms::owner_all);
    ASSERT_EQ(shell("ssh-keygen -q -t ed25519 -N '' -f " + (ssh / "host_key").string() + " && ssh-keygen -q -t ed25519 -N '' -f " +
                    (ssh / "id_ed25519").string() + " && ssh-keygen -q -t ed25519 -N '' -f " + (ssh / "outsider_ed25519").string() +
                    " && cp " + (ssh / "id_ed25519.pub").string() + " " + (ssh / "authorized_keys").string() + " && mkdir -p /run/sshd"),
              0);
    const std::string host_public = slurp((ssh / "host_key.pub").string());
    std::string known_hosts;
    for (int h = 2; h <= last; ++h) known_hosts += address(h) + " " + host_public;
    write_text(ssh / "known_hosts", known_hosts);
    write_text(ssh / "config", "Host *\n  User root\n  IdentityFile " + (ssh / "id_ed25519").string() +
                                   "\n  IdentitiesOnly yes\n  UserKnownHostsFile " + (ssh / "known_hosts").string() +
                                   "\n  StrictHostKeyChecking yes\n  GlobalKnownHostsFile /dev/null\n  LogLevel ERROR\n");
    for (int h = 2; h <= last; ++h) {
      const fs::path config = ssh / ("sshd_config-h" + std::to_string(h));
      write_text(config, "ListenAddress " + address(h) + "\nPort 22\nHostKey " + (ssh / "host_key").string() +
                             "\nAuthorizedKeysFile " + (ssh / "authorized_keys").string() + "\nPidFile " +
                             (ssh / ("sshd-h" + std::to_string(h) + ".pid")).string() +
                             "\nPermitRootLogin prohibit-password\nPasswordAuthentication no\nKbdInteractiveAuthentication no\n"
                             "UsePAM no\nStrictModes no\nPrintMotd no\n");
      const std::string log = (dir_ / ("sshd-h" + std::to_string(h) + ".log")).string();
      sshds_.push_back(spawn({ip_command(), "netns", "exec", ns(h), "/usr/sbin/sshd", "-D", "-e", "-f", config.string()}, log));
      bool listening = false;
      for (int i = 0; i < 100 && !listening; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        listening = slurp(log).find("Server listening on " + address(h)) != std::string::npos;
      }
      ASSERT_TRUE(listening) << slurp(log);
    }
    over_ssh_ = true;
  }
  fs::path ssh_config() const { return dir_ / "ssh" / "config"; }

  // The --set options that make host h of a launch: its address, and how it is reached.
  std::vector<std::string> host_args(int h) const {
    const std::string key = "hosts.h" + std::to_string(h);
    std::vector<std::string> out{"--set", key + ".address=" + address(h)};
    if (h == 1) return out;
    if (over_ssh_) return {out[0], out[1], "--set", key + ".ssh_config=" + ssh_config().string()};
    return {out[0], out[1], "--set", key + ".control=dds_agent"};
  }

  static void write_text(const fs::path& path, const std::string& text) {
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr) << path;
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }

  void stop_agents() {
    for (pid_t pid : agents_) ::kill(pid, SIGTERM);
    for (pid_t pid : agents_) {
      const CommandResult r = wait_for(pid, "/dev/null", 10);
      EXPECT_FALSE(r.timed_out) << "an agent did not stop on SIGTERM";
    }
    agents_.clear();
    for (pid_t pid : sshds_) ::kill(pid, SIGTERM);
    for (pid_t pid : sshds_) wait_for(pid, "/dev/null", 10);
    sshds_.clear();
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
      const auto keys = host_args(static_cast<int>(i) + 1);
      argv.insert(argv.end(), keys.begin(), keys.end());
      argv.insert(argv.end(), {"--set", "participants." + participants[i] + ".host=" + host});
    }
    argv.insert(argv.end(), extra.begin(), extra.end());
    return run(argv, (runs.string() + ".log"), 240);
  }

  // The K-station line shaft (`mechsim scene stations`) into <dir>/line_shaft_K.yaml, run on
  // this machine's loopback into <dir>/single: the bytes a multi-host run must reproduce.
  void line_shaft_single_host_run(int stations, std::string& scene) {
    scene = (dir_ / ("line_shaft_" + std::to_string(stations) + ".yaml")).string();
    const CommandResult gen = run({kMechsim, "scene", "stations", "--stations", std::to_string(stations), "-o", scene},
                                  (dir_ / "generate.log").string(), 30);
    ASSERT_EQ(gen.exit_code, 0) << gen.output;
    const fs::path single = dir_ / "single";
    const CommandResult one =
        run({kMechsim, "launch", scene, "--runs-dir", single.string(), "--no-plot", "--no-progress", "--ready-timeout", "300"},
            single.string() + ".log", 600);
    ASSERT_EQ(one.exit_code, 0) << one.output;
  }

  // Waits up to 10 s until host 1 holds no process and hosts 2 and 3 one each (the agent or
  // the sshd); true when they do, and a line saying what is left in `left`.
  bool only_one_process_left_on_hosts_2_and_3(std::string& left) {
    bool clean = false;
    for (int i = 0; i < 100 && !clean; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      clean = pids_in(ns(1)).empty() && pids_in(ns(2)).size() == 1 && pids_in(ns(3)).size() == 1;
    }
    left = "processes left: host 1 " + std::to_string(pids_in(ns(1)).size()) + ", host 2 " + std::to_string(pids_in(ns(2)).size()) +
           ", host 3 " + std::to_string(pids_in(ns(3)).size());
    return clean;
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
  bool over_ssh_ = false;
  std::vector<pid_t> agents_;
  std::vector<pid_t> sshds_;
};

}  // namespace mechsim::testing
