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
  std::string log(const std::string& tag) const { return (dir_ / (tag + ".log")).string(); }
  nlohmann::json summary(const std::string& tag) const {
    return nlohmann::json::parse(slurp((dir_ / (tag + ".json")).string()));
  }
  // The single run folder under <dir>/<tag>.
  std::filesystem::path run_folder(const std::string& tag) const {
    for (const auto& e : std::filesystem::directory_iterator(dir_ / tag)) return e.path();
    return {};
  }
  std::filesystem::path dir_;
};

}  // namespace mechsim::testing
