// `mechsim cam-design SCENE --lift-off-sweep` end to end: the flexible follower's actual
// lift-off speed from a bisection over real distributed runs (`mechsim launch`, node
// processes over loopback DDS), beside the kinetostatic prediction of the same follower.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class CamLiftOffSweep : public RunFolderTest {};

TEST_F(CamLiftOffSweep, FlexibleFollowerLiftsOffBelowTheKinetostaticSpeed) {
  // A coarse sweep (6 runs of 2 revolutions, ~1 s each unloaded) over a range that holds the
  // bounds argued below: 50 rpm lies above the lower bound, 110 rpm above the upper one.
  const std::string report = (dir_ / "sweep.json").string();
  CommandResult r = run({kMechsim, "cam-design", scene_path("cam_lift_off.yaml"), "--lift-off-sweep", "--sweep-range",
                         "50 rpm..110 rpm", "--sweep-tol", "4 rpm", "--runs-dir", (dir_ / "runs").string(), "--json",
                         report},
                        log("sweep"), 240);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json j = json::parse(slurp(report));
  const json& s = j["lift_off_sweep"];
  ASSERT_EQ(s["outcome"], "found") << s.dump(1);

  // Consistency of what is reported: the bracket is [highest run without lift-off, lowest
  // run with it], at most the tolerance wide, the simulated speed is its upper end, and the
  // kinetostatic speed beside it is the report's own (same scene, same follower).
  const double low = s["bracket_rpm"][0].get<double>(), high = s["bracket_rpm"][1].get<double>();
  const double simulated = j["lift_off_speed_simulated_rpm"].get<double>();
  const double kinetostatic = j["lift_off_speed_rpm"].get<double>();
  EXPECT_DOUBLE_EQ(simulated, high);
  EXPECT_LE(high - low, 4.0);
  EXPECT_NEAR(s["bracket_width_rpm"].get<double>(), high - low, 1e-9);  // rpm from rad/s and back
  EXPECT_DOUBLE_EQ(s["kinetostatic_lift_off_speed_rpm"].get<double>(), kinetostatic);
  EXPECT_FALSE(s["follower_has_loads"].get<bool>());
  // 60 rpm halved 4 times is 3.75 rpm <= 4: the two ends and 4 bisection runs.
  ASSERT_EQ(s["runs"].size(), 6u);
  // One progress line per run.
  for (int i = 1; i <= 6; ++i)
    EXPECT_NE(r.output.find("lift-off sweep: run " + std::to_string(i) + "/6 at"), std::string::npos) << r.output;
  double slowest_lift = INFINITY, fastest_no_lift = 0.0;
  int index = 0;
  for (const auto& run : s["runs"]) {
    ++index;
    const double v = run["speed_rpm"].get<double>();
    const bool lifted = run["lifted_off"].get<bool>();
    EXPECT_EQ(lifted, run["lift_off_count"].get<int>() > 0);
    EXPECT_GT(run["wall_time_s"].get<double>(), 0.0);
    (lifted ? slowest_lift : fastest_no_lift) = lifted ? std::min(slowest_lift, v) : std::max(fastest_no_lift, v);
    // Each run is a real distributed run, and the monolithic reference the launcher runs
    // beside it agrees on whether the follower lifts off (the event is found by root finding
    // in both; no speed of this sweep lies within 0.5 rpm of the transition, ten times what
    // the co-simulation's macro step moves it: < 0.05 rpm between 0.25 ms and 1 ms).
    char tag[32];
    std::snprintf(tag, sizeof tag, "run-%02d.json", index);
    fs::path summary_file;
    for (const auto& e : fs::directory_iterator(dir_ / "runs"))
      if (fs::exists(e.path() / tag)) summary_file = e.path() / tag;
    ASSERT_FALSE(summary_file.empty()) << tag;
    const json summary = json::parse(slurp(summary_file.string()));
    EXPECT_EQ(summary["status"], "ok");
    EXPECT_EQ(summary["reference"]["event_counts"].value("follower.lift_off", 0) > 0, lifted) << "at " << v << " rpm";
  }
  EXPECT_DOUBLE_EQ(slowest_lift, high);
  EXPECT_DOUBLE_EQ(fastest_no_lift, low);

  // Upper bound: at the kinetostatic speed (106.5 rpm) the rigid follower's contact force just
  // touches zero (at 158.9 deg, in the fall). The flexible follower's contact force is that
  // plus its vibration, which the short C1 rise and the fall excite with either sign, so it
  // cannot keep the contact up to that speed: lift-off at or below it.
  EXPECT_LE(simulated, kinetostatic);
  // Lower bound: the vibration is the response of the contact (zeta = 0.08 in
  // cam_lift_off.yaml) to the same inertia demand m S'' w^2 that the rigid analysis sees; a
  // lightly damped oscillator amplifies an excitation at most by its resonance peak
  // 1/(2 zeta) (the steady, worst case: the transient of one lift event amplifies less). The
  // contact force is therefore at least F0 + k S - (1 + 1/(2 zeta)) m |S''| w^2, which stays
  // positive below w_kin / sqrt(1 + 1/(2 zeta)) = 106.5 / 2.69 = 39.6 rpm.
  // The bracket's low end is a run without lift-off (the range's low end, 50 rpm, had to
  // be one for outcome "found"), so the lift-off speed lies above it.
  constexpr double zeta = 0.08;
  EXPECT_GT(low, kinetostatic / std::sqrt(1.0 + 1.0 / (2.0 * zeta)));
  // The first lift-off is reported with its angle, within the cycle.
  const double angle = j["lift_off_simulated_angle_deg"].get<double>();
  EXPECT_GE(angle, 0.0);
  EXPECT_LT(angle, 360.0);
  std::printf("lift-off speed: simulated %.2f rpm (bracket %.2f..%.2f, first at %.1f deg), kinetostatic %.2f rpm; "
              "sweep %.1f s\n",
              simulated, low, high, angle, kinetostatic, s["wall_time_s"].get<double>());
}

TEST_F(CamLiftOffSweep, RigidFollowerIsRefusedBeforeAnyRun) {
  CommandResult r = run({kMechsim, "cam-design", scene_path("cam_press.yaml"), "--lift-off-sweep", "--runs-dir",
                         (dir_ / "runs").string()},
                        log("rigid"), 60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("participants.follower.params.model"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "runs"));
}

}  // namespace
}  // namespace mechsim::testing
