// The NC position loop closed across three processes (servo amplifier | motor + tacho |
// slide), against the monolithic reference and the spec's figures; and a macro step
// beyond the coupling's stability limit stopping with a message instead of garbage.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class NcLoop : public RunFolderTest {
 protected:
  CommandResult launch(const std::string& scene_file, std::vector<std::string> extra = {}) {
    return run(launch_args(scene_path(scene_file), "nc", std::move(extra)), log("nc"), 180);
  }
  json summary() const { return RunFolderTest::summary("nc"); }
};

TEST_F(NcLoop, ShippedStepSceneIsStableAndAccurateAsShipped) {
  CommandResult r = launch("nc_slide_loop.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json s = summary();
  const json& step = figure(s, "step_response", "slide.slide_position");
  const json& ref = step["reference"];
  // The monolithic reference against spec nc_slide.md §3 (continuous controller): rise
  // 34.4 ms, no overshoot, 2 % settling 94.7 ms; +-3 % as the issue allows for a model
  // whose constants were identified to three digits.
  EXPECT_NEAR(ref["rise_time_s"].get<double>(), 0.0344, 0.03 * 0.0344);
  EXPECT_NEAR(ref["settling_time_s"].get<double>(), 0.0947, 0.03 * 0.0947);
  EXPECT_LT(ref["overshoot_pct"].get<double>(), 1e-6);
  // Distributed against the reference (issue 4, "the stiff cut"): rise time and final
  // position within 1 %, settling within 2 %.
  EXPECT_LT(step["relative_difference"]["rise_time_s"].get<double>(), 0.01);
  EXPECT_LT(step["relative_difference"]["settling_time_s"].get<double>(), 0.02);
  EXPECT_LT(std::abs(step["final_value"].get<double>() - ref["final_value"].get<double>()), 0.01 * 1e-4);
  EXPECT_TRUE(step["settled"].get<bool>());
}

// 200 us is twice the measured limit of the compliant coupling with the cut extrapolated
// linearly and the electrical edges held (docs/nc-loop.md), the scheme the scene shipped
// before issue 31, pinned here for that margin. The shipped scheme (edges linear, cut
// quadratic) is stable to 176 us and also diverges at 200 us (docs/stability.md).
std::vector<std::string> beyond_the_stability_limit(std::vector<std::string> more = {}) {
  std::vector<std::string> args{"--step", "200 us", "--set", "connections[0].reconstruction=hold", "--set",
                                "connections[1].reconstruction=hold", "--set", "connections[2].reconstruction=hold", "--set",
                                "connections[3].reconstruction=linear", "--set", "connections[4].reconstruction=linear"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

void expect_stopped_with_advice(const CommandResult& r) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("diverged"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tacho -> slide"), std::string::npos) << r.output;  // the connection
  // A step to try: the launcher halves the step in process until a run is stable; 100 us
  // lies below the measured limit (105-110 us), so that is the step it names.
  EXPECT_NE(r.output.find("--step '100 us'"), std::string::npos) << r.output;
}

TEST_F(NcLoop, AMacroStepBeyondTheStabilityLimitStopsWithAdvice) {
  expect_stopped_with_advice(launch("nc_slide_loop.yaml", beyond_the_stability_limit()));
}

// Status travels best effort; on a loaded machine the failed node's last one was lost and
// the run stopped without advice (CI, stop 35). The exit code says it diverged
// (docs/protocol.md, "Failures"): every node here fails without a failed status.
TEST_F(NcLoop, TheAdviceNeedsNoStatusFromTheNodeThatDiverged) {
  std::vector<std::string> lose;
  for (const char* node : {"servo", "tacho", "slide"})
    lose.insert(lose.end(), {"--set", std::string("participants.") + node + ".testing.lose_failed_status=true"});
  const CommandResult r = launch("nc_slide_loop.yaml", beyond_the_stability_limit(lose));
  expect_stopped_with_advice(r);
  EXPECT_NE(r.output.find("exit code 4"), std::string::npos) << r.output;
}

TEST_F(NcLoop, FollowingErrorAtConstantFeedIsVelocityOverGain) {
  CommandResult r = launch("nc_slide_move.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Spec §3: at constant feed without feed-forward the following error is v/K_v =
  // 0.1 m/s / 40 1/s = 2.5 mm; the transient adds nothing at the end of the cruise, so
  // the largest error is that value to within 1 % (the position measurement lags through
  // the spindle twist by micrometres).
  EXPECT_NEAR(figure(summary(), "max_abs", "servo.following_error")["value"].get<double>(), 2.5e-3, 0.01 * 2.5e-3);
  CommandResult ff = launch("nc_slide_move.yaml", {"--set", "servo.velocity_feedforward=1"});
  ASSERT_EQ(ff.exit_code, 0) << ff.output;
  // With full feed-forward the steady following error vanishes; what is left comes from
  // the acceleration phases: an order of magnitude below v/K_v.
  EXPECT_LT(figure(summary(), "max_abs", "servo.following_error")["value"].get<double>(), 0.25e-3);
}

}  // namespace
}  // namespace mechsim::testing
