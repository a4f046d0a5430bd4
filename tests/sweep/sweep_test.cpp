// `mechsim sweep` as a user runs it: a 2 x 2 grid on the cam press (0.2 s, 200 steps), one
// key's second value refused by the scene, the table's rows, --resume, and bad input
// refused before any point runs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kMechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
const std::string kScene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cam_press.yaml";

CommandResult sweep(const std::vector<std::string>& args, const std::string& log) {
  std::vector<std::string> argv{kMechsim, "sweep", kScene, "--set", "time.end=0.2 s"};
  argv.insert(argv.end(), args.begin(), args.end());
  return run(argv, log, 240);
}

json read_json(const std::string& path) {
  std::ifstream f(path);
  return json::parse(f, nullptr, false);
}

class SweepGrid : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("mechsim-sweep-test-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  std::vector<std::string> grid() const {
    return {"--vary", "follower.spring.preload=100 N,150 N", "--vary", "follower.mass=25 kg,-1 kg", "--jobs", "2",
            "--out", (dir_ / "out").string()};
  }
  fs::path dir_;
};

TEST_F(SweepGrid, TableHasEveryPointRefusedOnesWithTheirReason) {
  const CommandResult r = sweep(grid(), (dir_ / "sweep.log").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json table = read_json((dir_ / "out/sweep.json").string());
  ASSERT_TRUE(table.is_object()) << r.output;
  const json& rows = table["rows"];
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(table["counts"]["ok"], 2);
  EXPECT_EQ(table["counts"]["refused"], 2);
  // Grid order: the last key fastest; the mass of -1 kg is refused by the scene's check.
  for (int i = 0; i < 4; ++i) {
    const json& row = rows[i];
    EXPECT_EQ(row["point"], i);
    EXPECT_EQ(row["follower.spring.preload.text"], i < 2 ? "100 N" : "150 N");
    EXPECT_EQ(row["follower.mass.text"], i % 2 == 0 ? "25 kg" : "-1 kg");
    if (i % 2 == 1) {
      EXPECT_EQ(row["outcome"], "refused");
      EXPECT_NE(row["reason"].get<std::string>().find("participants.follower.params.mass"), std::string::npos) << row["reason"];
      EXPECT_EQ(row["steps"], 0);
      continue;
    }
    EXPECT_EQ(row["outcome"], "ok") << row["reason"];
    EXPECT_EQ(row["steps"], 200);  // 0.2 s at 1 ms
    // Gauss-Seidel cam -> follower with the torque held: the contact force of a rigid follower
    // is of the order of its reference (cam_press summaries: 1e-5..1e-2 of the range).
    ASSERT_TRUE(row["worst_max_rel_error"].is_number());
    EXPECT_LT(row["worst_max_rel_error"].get<double>(), 0.05);
    EXPECT_FALSE(row["worst_max_rel_signal"].get<std::string>().empty());
    EXPECT_TRUE(fs::exists(dir_ / ("out/points/0000" + std::to_string(i)) / "summary.json"));
  }
  // The rigid follower's motion is the cam's, whatever the force: 50 N more preload is 50 N
  // more contact force at every instant, so the minimum moves by 50 N to roundoff.
  const double min100 = rows[0]["min(follower.contact_force)"], min150 = rows[2]["min(follower.contact_force)"];
  EXPECT_NEAR(min150 - min100, 50.0, 1e-6);
  // The CSV: a header and a line per point.
  std::ifstream csv(dir_ / "out/sweep.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 5);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_TRUE(fs::exists(dir_ / "out/plots/follower.spring.preload.png")) << r.output;
  }

  // --resume: every point is finished, none runs again; the table is the same.
  const auto summary = dir_ / "out/points/00000/summary.json";
  const auto written = fs::last_write_time(summary);
  std::vector<std::string> again = grid();
  again.push_back("--resume");
  const CommandResult r2 = sweep(again, (dir_ / "resume.log").string());
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  EXPECT_NE(r2.output.find("4 finished before, 0 to run"), std::string::npos) << r2.output;
  EXPECT_EQ(fs::last_write_time(summary), written);
  EXPECT_EQ(read_json((dir_ / "out/sweep.json").string())["rows"], rows);

  // --resume into a folder of another study is refused.
  std::vector<std::string> other{"--vary", "follower.spring.preload=100 N,160 N", "--out", (dir_ / "out").string(), "--resume"};
  const CommandResult r3 = sweep(other, (dir_ / "other.log").string());
  EXPECT_EQ(r3.exit_code, 2);
  EXPECT_NE(r3.output.find("holds another study"), std::string::npos) << r3.output;
}

// The NC loop beyond its stability limit (about 110 us: docs/nc-loop.md) diverges: a row
// with the step it stopped at, and the sweep goes on to its other point.
TEST_F(SweepGrid, ADivergingPointIsARowWithItsReason) {
  const std::string nc = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_slide_loop.yaml";
  const CommandResult r = run({kMechsim, "sweep", nc, "--set", "time.end=0.05 s", "--vary", "time.step=25 us,200 us", "--out",
                               (dir_ / "nc").string(), "--no-plot"},
                              (dir_ / "nc.log").string(), 240);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json rows = read_json((dir_ / "nc/sweep.json").string())["rows"];
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["outcome"], "ok") << rows[0]["reason"];
  EXPECT_EQ(rows[0]["steps"], 2000);  // 0.05 s at 25 us
  EXPECT_EQ(rows[1]["outcome"], "diverged");
  EXPECT_NE(rows[1]["reason"].get<std::string>().find("diverged"), std::string::npos) << rows[1]["reason"];
  EXPECT_GT(rows[1]["steps"].get<int>(), 0);
  EXPECT_LT(rows[1]["steps"].get<int>(), 250);  // stopped before the end at 200 us
  EXPECT_TRUE(rows[1]["worst_max_rel_error"].is_null());
}

TEST_F(SweepGrid, BadInputIsRefusedBeforeAnyPointRuns) {
  const auto refused = [&](const std::vector<std::string>& args, const std::string& expected) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"--out", (dir_ / "bad").string()});
    const CommandResult r = sweep(a, (dir_ / "bad.log").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad/points"));
  };
  refused({"--vary", "follower.bogus=1,2"}, "unknown key 'bogus'");
  refused({"--vary", "follower.mass=1..4:1"}, "empty range");
  refused({"--vary", "follower.mass=-2 kg,-1 kg"}, "refuses every point");
  refused({"--vary", "follower.mass=1..4 kg", "--method", "lhs"}, "needs --samples");
}

}  // namespace
}  // namespace mechsim::testing
