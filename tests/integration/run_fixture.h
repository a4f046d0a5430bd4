// Test fixture for tests that launch real processes: a fresh temporary folder per test
// (run folders, logs, summaries go there), and a check at the end that no process of the
// test is left behind.
#pragma once

#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_command.h"

namespace mechsim::testing {

inline const std::string kMechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
inline std::string scene_path(const std::string& name) {
  return std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + name;
}

// The node outputs of two run folders are the same bytes, node by node (and not next to
// empty: over 1000 bytes); `what` names the two runs in a failure.
inline void expect_identical_node_outputs(const std::filesystem::path& a, const std::filesystem::path& b,
                                          const std::vector<std::string>& nodes, const std::string& what) {
  for (const auto& node : nodes) {
    const std::string name = node + ".outputs.bin";
    const std::string first = slurp((a / name).string()), second = slurp((b / name).string());
    EXPECT_GT(first.size(), 1000u) << name;
    EXPECT_TRUE(first == second) << name << " differs between " << what << " (" << first.size() << " vs " << second.size()
                                 << " bytes)";
  }
}
// The same for every node of `summary` (a launcher summary).
inline void expect_identical_node_outputs(const std::filesystem::path& a, const std::filesystem::path& b,
                                          const nlohmann::json& summary, const std::string& what) {
  ASSERT_FALSE(summary.is_null());
  std::vector<std::string> nodes;
  for (const auto& [node, info] : summary["nodes"].items()) nodes.push_back(node);
  expect_identical_node_outputs(a, b, nodes, what);
}

// The figure `stat` of `signal` in a run summary's error report (a test failure if absent).
inline const nlohmann::json& figure(const nlohmann::json& s, const std::string& stat, const std::string& signal) {
  for (const auto& f : s["report"])
    if (f["stat"] == stat && f["signal"] == signal) return f;
  static const nlohmann::json none;
  ADD_FAILURE() << "no figure " << stat << " " << signal;
  return none;
}

class RunFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("mechsim-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    // Whatever happened, nothing of this test may still run.
    EXPECT_TRUE(processes_mentioning(dir_.string()).empty()) << "processes left behind";
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }
  // `mechsim launch SCENE` with run folders under <dir>/<tag>, the summary in <dir>/<tag>.json
  // and the output in <dir>/<tag>.log.
  std::vector<std::string> launch_args(const std::string& scene_file, const std::string& tag,
                                       std::vector<std::string> extra = {}) const {
    std::vector<std::string> a{kMechsim, "launch", scene_file, "--runs-dir", (dir_ / tag).string(),
                               "--json", (dir_ / (tag + ".json")).string(), "--no-plot", "--no-progress"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  // The same with every participant in a process of its own (`processes: per_participant`),
  // for tests that kill, stop or read the log of one node's process: by default the
  // launcher puts a single host's participants of a vendor into one process.
  std::vector<std::string> launch_args_a_process_each(const std::string& scene_file, const std::string& tag,
                                                      std::vector<std::string> extra = {}) const {
    extra.insert(extra.end(), {"--set", "processes=per_participant"});
    return launch_args(scene_file, tag, std::move(extra));
  }
  std::string log(const std::string& tag) const { return (dir_ / (tag + ".log")).string(); }
  nlohmann::json summary(const std::string& tag) const {
    return nlohmann::json::parse(slurp((dir_ / (tag + ".json")).string()));
  }
  // The single run folder under <dir>/<tag>.
  std::filesystem::path run_folder(const std::string& tag) const {
    for (const auto& e : std::filesystem::directory_iterator(dir_ / tag)) return e.path();
    return {};
  }
  // The run folder under <dir>/<tag> once the launcher made it; empty after 30 s.
  std::filesystem::path wait_for_run_folder(const std::string& tag) const {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < until) {
      std::error_code ec;
      for (std::filesystem::directory_iterator it(dir_ / tag, ec), end; !ec && it != end;) return it->path();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return {};
  }
  // Waits until <node>.outputs.bin in the run folder under <dir>/<tag> holds at least
  // `bytes` bytes (rows the node has written: the event a test needs, e.g. "the run is
  // stepping" or "it is past t"). False when `alive` (the launcher) ended first or after
  // `timeout_s`, a guard against a hang and not a measurement.
  bool wait_for_output_bytes(const std::string& tag, const std::string& node, std::uintmax_t bytes, double timeout_s,
                             pid_t alive = 0) const {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < until) {
      if (output_bytes(dir_ / tag, node) >= bytes) return true;
      if (alive > 0 && has_exited(alive)) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
  // True once the child `pid` has exited (it is left to wait_for to reap).
  static bool has_exited(pid_t pid) {
    siginfo_t info{};
    return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
  }
  std::filesystem::path dir_;
};

}  // namespace mechsim::testing
