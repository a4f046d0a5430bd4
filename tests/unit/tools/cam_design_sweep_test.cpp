// The lift-off sweep's pure parts (tools/analyses/cam_design/cam_lift_off_sweep.h): the
// bisection over a lift-off predicate, the overrides of one run, the reading of a run
// summary and the JSON. The distributed runs themselves are tested in
// tests/integration/cam_lift_off_sweep_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cam_design_report.h"
#include "cam_lift_off_sweep.h"
#include "mechsim/config/scene.h"

namespace mechsim::tools::cam_design {
namespace {

using nlohmann::json;
constexpr double rpm = 2.0 * std::numbers::pi / 60.0;

std::string scene_file(const std::string& name) { return std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + name; }

// A follower that lifts off from `threshold` on, as a run would report it.
LiftOffRun threshold_run(double speed, double threshold) {
  LiftOffRun r;
  r.speed_rad_s = speed;
  r.lift_offs = speed >= threshold ? 3 : 0;
  if (r.lifted_off()) r.first_lift_off_angle_deg = 48.9;
  r.wall_time_s = 1.0;
  return r;
}

TEST(LiftOffBisection, BracketsAMonotoneThresholdWithinTheTolerance) {
  const LiftOffSweepSettings settings{50 * rpm, 110 * rpm, 0.5 * rpm, 2};
  const double threshold = 73.1 * rpm;
  std::vector<double> reported;
  const LiftOffSearch s = find_lift_off_speed(
      settings, [&](double v) { return threshold_run(v, threshold); },
      [&](const LiftOffRun& r) { reported.push_back(r.speed_rad_s); });
  ASSERT_EQ(s.outcome, LiftOffOutcome::found);
  ASSERT_TRUE(s.low_rad_s && s.high_rad_s);
  EXPECT_LT(*s.low_rad_s, threshold);
  EXPECT_GE(*s.high_rad_s, threshold);
  EXPECT_LE(*s.high_rad_s - *s.low_rad_s, settings.tolerance_rad_s);
  // Ends first, then halvings: 60 rpm halved 7 times is 0.47 rpm <= 0.5 rpm, 6 times 0.94.
  ASSERT_EQ(s.runs.size(), 9u);
  EXPECT_EQ(max_sweep_runs(settings), 9);
  EXPECT_EQ(s.runs[0].speed_rad_s, settings.low_rad_s);
  EXPECT_EQ(s.runs[1].speed_rad_s, settings.high_rad_s);
  EXPECT_DOUBLE_EQ(s.runs[2].speed_rad_s, 80 * rpm);
  EXPECT_EQ(reported.size(), s.runs.size());  // one progress call per run
}

TEST(LiftOffBisection, ARangeThatMissesTheThresholdSaysOnWhichSide) {
  const LiftOffSweepSettings settings{50 * rpm, 110 * rpm, 1 * rpm, 2};
  // Lifts off at any speed (a follower with load steps): one run, the low end.
  const LiftOffSearch below = find_lift_off_speed(settings, [](double v) { return threshold_run(v, 0.0); });
  EXPECT_EQ(below.outcome, LiftOffOutcome::lifts_off_at_range_low);
  EXPECT_EQ(below.runs.size(), 1u);
  EXPECT_FALSE(below.low_rad_s);
  EXPECT_EQ(*below.high_rad_s, settings.low_rad_s);
  // Never lifts off in the range: the two ends.
  const LiftOffSearch above = find_lift_off_speed(settings, [](double v) { return threshold_run(v, 1e9); });
  EXPECT_EQ(above.outcome, LiftOffOutcome::no_lift_off_at_range_high);
  EXPECT_EQ(above.runs.size(), 2u);
  EXPECT_EQ(*above.low_rad_s, settings.high_rad_s);
  EXPECT_FALSE(above.high_rad_s);
}

TEST(LiftOffBisection, ANonMonotoneFollowerStillGivesATransition) {
  // Lift-off in a window 60..70 rpm and again from 90 rpm: whatever the bisection lands
  // on, the bracket's low end was run without lift-off and its high end with it.
  auto lifts = [](double v) { return (v >= 60 * rpm && v < 70 * rpm) || v >= 90 * rpm; };
  const LiftOffSearch s = find_lift_off_speed({50 * rpm, 110 * rpm, 0.5 * rpm, 2}, [&](double v) {
    LiftOffRun r;
    r.lift_offs = lifts(v) ? 1 : 0;
    return r;
  });
  ASSERT_EQ(s.outcome, LiftOffOutcome::found);
  EXPECT_FALSE(lifts(*s.low_rad_s));
  EXPECT_TRUE(lifts(*s.high_rad_s));
  EXPECT_LE(*s.high_rad_s - *s.low_rad_s, 0.5 * rpm);
}

TEST(LiftOffBisection, RefusesABadRangeNamingTheOption) {
  auto message = [](const LiftOffSweepSettings& s) {
    try {
      validate(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({110 * rpm, 50 * rpm, 1 * rpm, 2}).find("--sweep-range"), std::string::npos);
  EXPECT_NE(message({0.0, 50 * rpm, 1 * rpm, 2}).find("--sweep-range"), std::string::npos);
  EXPECT_NE(message({50 * rpm, 110 * rpm, 0.0, 2}).find("--sweep-tol"), std::string::npos);
  EXPECT_NE(message({50 * rpm, 110 * rpm, 1 * rpm, 0.5}).find("--sweep-revolutions"), std::string::npos);
  EXPECT_EQ(message({50 * rpm, 110 * rpm, 1 * rpm, 1}), "accepted");
  // The default range scales the kinetostatic speed; without one there is nothing to scale.
  const auto d = default_sweep_range({10.0, 1.0, 0.0}, 0.05, 2);
  EXPECT_DOUBLE_EQ(d.low_rad_s, 5.0);
  EXPECT_DOUBLE_EQ(d.high_rad_s, 15.0);
  EXPECT_THROW(default_sweep_range({INFINITY, 0.0, 0.0}, 0.05, 2), std::invalid_argument);
  EXPECT_THROW(default_sweep_range({0.0, 0.0, 0.0}, 0.05, 2), std::invalid_argument);
}

TEST(LiftOffRunSummary, CountsTheFollowersLiftOffsAndTakesTheEarliest) {
  const json summary = {
      {"status", "ok"},
      {"run_dir", "runs/x"},
      {"events",
       {{{"node", "follower"}, {"kind", "lift_off"}, {"t_s", 0.9}, {"angle_deg", 160.2}},
        {{"node", "follower"}, {"kind", "landing"}, {"t_s", 0.95}, {"angle_deg", 170.0}},
        {{"node", "follower"}, {"kind", "lift_off"}, {"t_s", 0.1}, {"angle_deg", 48.9}},
        {{"node", "other"}, {"kind", "lift_off"}, {"t_s", 0.01}, {"angle_deg", 1.0}}}}};
  const LiftOffRun r = lift_off_run_from_summary(summary, "follower", 7.7, 3.5);
  EXPECT_EQ(r.lift_offs, 2);
  EXPECT_EQ(r.landings, 1);
  EXPECT_DOUBLE_EQ(*r.first_lift_off_t_s, 0.1);
  EXPECT_DOUBLE_EQ(*r.first_lift_off_angle_deg, 48.9);
  EXPECT_EQ(r.run_dir, "runs/x");
  EXPECT_DOUBLE_EQ(r.wall_time_s, 3.5);
  // No events: no lift-off. A failed run or a summary without events is an error, never
  // "no lift-off".
  EXPECT_FALSE(lift_off_run_from_summary({{"status", "ok"}, {"events", json::array()}}, "follower", 1, 1).lifted_off());
  EXPECT_THROW(lift_off_run_from_summary({{"status", "failed"}, {"failure", {{"reason", "x"}}}}, "follower", 1, 1),
               std::runtime_error);
  EXPECT_THROW(lift_off_run_from_summary({{"status", "ok"}}, "follower", 1, 1), std::runtime_error);
}

TEST(LiftOffRunOverrides, SetTheCamSpeedAndWholeStepsOfTheRevolutions) {
  const config::Scene scene = config::load_scene(scene_file("cam_lift_off.yaml"));
  const CamDesignResult result = analyse_scene(scene);
  const double speed = 73.1 * rpm;  // 0.8208 s per revolution: not a whole number of 0.5 ms steps
  const auto overrides = lift_off_run_overrides(scene, result.roller->input_case, speed, 2);
  ASSERT_EQ(overrides.size(), 2u);
  EXPECT_EQ(overrides[0].rfind("participants.cam.params.speed=", 0), 0u) << overrides[0];
  // The scene loads with them (whole steps), at that speed, and covers the revolutions by
  // less than one macro step more.
  const config::Scene run = config::load_scene(scene_file("cam_lift_off.yaml"), overrides);
  const double two_revolutions = 2 * 2 * std::numbers::pi / speed;
  EXPECT_GE(run.time.end, two_revolutions);
  EXPECT_LT(run.time.end, two_revolutions + run.time.step);
  EXPECT_NEAR(analyse_scene(run).roller->input_case.input.speed_rad_s, speed, 1e-12 * speed);
}

TEST(LiftOffRunOverrides, RefuseARigidFollowerAndATorqueDrive) {
  auto refusal = [](const std::string& file, const std::vector<std::string>& overrides) {
    const config::Scene scene = config::load_scene(scene_file(file), overrides);
    try {
      lift_off_run_overrides(scene, analyse_scene(scene).roller->input_case, 8.0, 2);
    } catch (const config::ConfigError& e) {
      return e.key_path();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("cam_press.yaml", {}), "participants.follower.params.model");
  EXPECT_EQ(refusal("cam_press_flywheel.yaml",
                    {"participants.follower.params.model=flexible",
                     "participants.follower.params.flexible.stiffness=574.19 N/mm"}),
            "participants.cam.params.drive");
  EXPECT_EQ(refusal("cam_press_flexible.yaml", {}), "accepted");
}

TEST(LiftOffSweepJson, ReportsTheBracketBesideBothKinetostaticSpeeds) {
  // The report scene's follower (with its loads); a made-up search at 0.5 rpm.
  const config::Scene scene = config::load_scene(scene_file("cam_press_flexible.yaml"));
  const CamDesignResult result = analyse_scene(scene);
  const RollerCase& c = result.roller->input_case;
  const LiftOffSweepSettings settings{50 * rpm, 110 * rpm, 0.5 * rpm, 2};
  const LiftOffSearch search =
      find_lift_off_speed(settings, [](double v) { return threshold_run(v, 73.1 * rpm); });
  json report = json::object();
  add_lift_off_sweep_json(report, settings, search, models::cam::MotionLaw(c.input.segments), c.input.follower,
                          c.follower_participant, 12.0);
  const json& sweep = report["lift_off_sweep"];
  EXPECT_EQ(sweep["outcome"], "found");
  EXPECT_DOUBLE_EQ(report["lift_off_speed_simulated_rpm"].get<double>(), sweep["bracket_rpm"][1].get<double>());
  EXPECT_DOUBLE_EQ(report["lift_off_simulated_angle_deg"].get<double>(), 48.9);
  EXPECT_LE(sweep["bracket_width_rpm"].get<double>(), sweep["tolerance_rpm"].get<double>());
  EXPECT_EQ(sweep["runs"].size(), search.runs.size());
  EXPECT_EQ(sweep["run_count"], search.runs.size());
  EXPECT_TRUE(sweep["follower_has_loads"].get<bool>());
  // With the loads: the report's 106.5 rpm (docs/cam-design.md, to its 4 digits).
  EXPECT_NEAR(sweep["kinetostatic_lift_off_speed_rpm"].get<double>(), 106.5, 0.05);
  EXPECT_NEAR(sweep["kinetostatic_lift_off_angle_deg"].get<double>(), 158.9, 0.05);
  // Without them: the critical angle at 158.9 deg lies in the fall, where no load acts, so
  // dropping the loads can only add candidates where loads pressed the follower on (+100 N
  // over 45..100 deg); the speed cannot rise.
  EXPECT_LE(sweep["kinetostatic_lift_off_speed_no_loads_rpm"].get<double>(),
            sweep["kinetostatic_lift_off_speed_rpm"].get<double>() + 1e-9);
  EXPECT_NEAR(sweep["simulated_to_kinetostatic"].get<double>(),
              report["lift_off_speed_simulated_rpm"].get<double>() / sweep["kinetostatic_lift_off_speed_rpm"].get<double>(),
              1e-12);
}

}  // namespace
}  // namespace mechsim::tools::cam_design
