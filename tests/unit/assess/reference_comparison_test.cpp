// A run against the monolithic reference (libs/assess reference_comparison.h), on node logs
// written from the reference itself: every error is zero, and an offset put into one log is
// the error found. Also the reference's accuracy per signal (reference_accuracy.h).
#include "mechsim/assess/reference_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "mechsim/cosim/output_log.h"

namespace mechsim::assess {
namespace {

std::string cam_press() { return std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cam_press.yaml"; }

// Writes, for every node of the plan, the log a node process writes (t and its block's
// outputs), with the reference's values; `offset` is added to one signal.
void write_logs_from(const cosim::ScenePlan& plan, const cosim::ReferenceRun& ref, const std::string& dir,
                     const std::string& offset_signal = "", double offset = 0.0) {
  for (const auto& node : plan.nodes()) {
    std::vector<std::string> columns;  // the writer puts "t" first
    for (const auto& o : node.block->outputs()) columns.push_back(o.name);
    cosim::OutputLogWriter log(dir + "/" + node.name() + ".outputs.bin", columns);
    std::vector<double> row(columns.size());
    for (std::size_t k = 0; k < ref.log.rows(); ++k) {
      for (std::size_t i = 0; i < columns.size(); ++i) {
        const std::string name = node.name() + "." + columns[i];
        const int c = ref.log.column(name);
        row[i] = c < 0 ? NAN : ref.log.data[c][k] + (name == offset_signal ? offset : 0.0);
      }
      log.append(ref.log.data[0][k], row);
    }
    log.close();
  }
}

class ReferenceComparisonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (std::filesystem::temp_directory_path() / ("mechsim-assess-" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(dir_);
    scene_ = config::load_scene(cam_press(), {"time.end=0.1 s"});
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
  config::Scene scene_;
};

TEST_F(ReferenceComparisonTest, LogsOfTheReferenceItselfHaveNoError) {
  cosim::ScenePlan plan = cosim::ScenePlan::build(scene_);
  const cosim::ReferenceRun ref = cosim::run_reference(plan);
  write_logs_from(plan, ref, dir_);
  const ReferenceComparison cmp = compare_with_reference(scene_, cosim::ScenePlan::build(scene_), dir_);
  // The reference is integrated again on the same grid with the same settings: the same numbers.
  EXPECT_EQ(cmp.t, ref.log.data[0]);
  ASSERT_EQ(cmp.signals.size(), scene_.compare.size());
  for (const auto& s : cmp.signals) {
    EXPECT_EQ(s.error.max_abs, 0.0) << s.signal.full_name();
    EXPECT_EQ(s.error.rms_abs, 0.0) << s.signal.full_name();
    EXPECT_TRUE(s.error.finite);
    EXPECT_FALSE(s.unit.empty());
    EXPECT_EQ(s.cosim, s.reference);
  }
  // Every report entry of cam_press is on a logged signal; the reference's figures are the run's.
  ASSERT_EQ(cmp.report.size(), scene_.report.size());
  for (const auto& f : cmp.report) {
    ASSERT_TRUE(f.difference);
    EXPECT_EQ(*f.difference->value, 0.0) << f.stat << " " << f.signal;
  }
  EXPECT_EQ(cmp.reference_accuracy.size(), scene_.compare.size());
  EXPECT_FALSE(cmp.suggested_scales);  // a fixed step
  EXPECT_TRUE(cmp.self_stepping.empty());
}

TEST_F(ReferenceComparisonTest, AnOffsetInOneLogIsItsError) {
  cosim::ScenePlan plan = cosim::ScenePlan::build(scene_);
  const cosim::ReferenceRun ref = cosim::run_reference(plan);
  const std::string offset_signal = scene_.compare.front().full_name();
  write_logs_from(plan, ref, dir_, offset_signal, 0.5);
  const ReferenceComparison cmp = compare_with_reference(scene_, cosim::ScenePlan::build(scene_), dir_);
  for (const auto& s : cmp.signals) {
    if (s.signal.full_name() != offset_signal) {
      EXPECT_EQ(s.error.max_abs, 0.0) << s.signal.full_name();
      continue;
    }
    // (x + 0.5) - x rounds by at most one ulp of x; the signals here stay below 1e4.
    EXPECT_NEAR(s.error.max_abs, 0.5, 1e-11);
    EXPECT_NEAR(s.error.rms_abs, 0.5, 1e-11);
    EXPECT_NEAR(s.error.max_rel, 0.5 / relative_scale(s.reference), 1e-11);
    EXPECT_FALSE(s.cause.one_step_late);  // a constant offset is no delay
  }
}

TEST(ReferenceAccuracy, DividesTheDifferenceByTheReferenceRange) {
  // A reference log of one signal ranging over [-1, 3] and an accuracy check that found a
  // difference of 0.02 (max) and 0.01 (rms): relative 0.005 and 0.0025. A signal the
  // reference did not log is left out.
  config::Scene scene;
  scene.compare = {{"a", "x", ""}, {"b", "unknown", ""}};
  cosim::ReferenceRun ref;
  ref.log.columns = {"t", "a.x"};
  ref.log.data = {{0.0, 1.0, 2.0}, {-1.0, 3.0, 0.0}};
  cosim::ReferenceAccuracy accuracy;
  accuracy.columns = {"a.x"};
  accuracy.max_abs = {0.02};
  accuracy.rms_abs = {0.01};
  const auto signals = reference_signal_accuracy(scene, ref, accuracy);
  ASSERT_EQ(signals.size(), 1u);
  EXPECT_EQ(signals[0].signal, "a.x");
  EXPECT_EQ(signals[0].max_abs, 0.02);
  EXPECT_EQ(signals[0].rms_abs, 0.01);
  EXPECT_DOUBLE_EQ(signals[0].max_rel, 0.005);
  EXPECT_DOUBLE_EQ(signals[0].rms_rel, 0.0025);
}

TEST(RelativeScale, RangeElseMagnitudeElseOne) {
  const std::vector<double> ramp{-1.0, 0.5, 3.0}, constant{-7.0, -7.0}, small{0.25, 0.25}, empty;
  EXPECT_EQ(relative_scale(ramp), 4.0);
  EXPECT_EQ(relative_scale(constant), 7.0);  // no range: the magnitude
  EXPECT_EQ(relative_scale(small), 1.0);     // and at least 1
  EXPECT_EQ(relative_scale(empty), 1.0);
}

}  // namespace
}  // namespace mechsim::assess
