// The stable-step trials (libs/assess stable_step.h) on the NC slide loop: the overrides that
// put a scene at a macro step, a trial that diverges beyond the loop's limit, and the halving
// search below it.
#include "mechsim/assess/stable_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace mechsim::assess {
namespace {

std::string shipped(const std::string& name) { return std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + name; }

TEST(AtMacroStep, SetsTheStepAWholeNumberOfStepsAndTheSampledAmplifier) {
  // nc_slide_loop_1ms: 0.2 s at 1 ms, the servo sampled at the macro step. At 0.3 ms the
  // run needs ceil(0.2 / 0.3e-3) = 667 steps, under kMinSteps: it lasts 2000 steps, 0.6 s.
  const std::string path = shipped("nc_slide_loop_1ms.yaml");
  const config::Scene base = config::load_scene(path);
  const double h = 0.3e-3;
  const config::Scene at = config::load_scene(path, at_macro_step(base, h, {}));
  EXPECT_NEAR(at.time.step, h, 1e-18);
  EXPECT_NEAR(at.time.end - at.time.start, kMinSteps * h, 1e-12);
  int sampled = 0;
  for (const auto& p : at.participants) {
    if (!p.params.has("sample_time")) continue;
    ++sampled;
    EXPECT_NEAR(p.params.child("sample_time").as_quantity(config::dim::time), h, 1e-18) << p.name;
  }
  EXPECT_EQ(sampled, 1);  // the servo amplifier
}

TEST(StableStep, BeyondTheLimitTheTrialDivergesAndTheSearchFindsAStableHalf) {
  // nc_slide_loop is stable at its 25 us and diverges at 200 us (README, "Try it"); the
  // search halves from 200 us and returns the first stable step, whose double is not.
  const std::string path = shipped("nc_slide_loop.yaml");
  const config::Scene base = config::load_scene(path);
  EXPECT_TRUE(try_macro_step(path, base, {}, 25e-6).stable);
  const StepTrial beyond = try_macro_step(path, base, {}, 200e-6);
  EXPECT_FALSE(beyond.stable);
  EXPECT_FALSE(beyond.why.empty());
  const auto found = find_stable_step_below(path, {}, 200e-6);
  ASSERT_TRUE(found);
  EXPECT_LT(*found, 200e-6);
  // A power-of-two fraction of 200 us.
  EXPECT_NEAR(std::log2(200e-6 / *found), std::round(std::log2(200e-6 / *found)), 1e-9);
  EXPECT_TRUE(try_macro_step(path, base, {}, *found).stable);
  EXPECT_FALSE(try_macro_step(path, base, {}, 2 * *found).stable);
}

}  // namespace
}  // namespace mechsim::assess
