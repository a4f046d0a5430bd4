// The flexible follower's actual lift-off speed (spec cam.md §5, issue 3 item 6), found by
// bisection over runs of the scene at constant cam speeds: the smallest speed at which the
// follower leaves the cam, beside the kinetostatic (rigid-follower) prediction of §3.
//
// This part is pure: the bisection over a predicate "the follower lifts off at speed ω",
// the scene overrides of one run, the reading of a run summary and the JSON. Running the
// scene distributed (`mechsim launch`) lives in cam_lift_off_launch.h.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cam_design_case.h"
#include "mechsim/config/scene.h"
#include "mechsim/models/cam/force_analysis.h"

namespace mechsim::tools::cam_design {

// What the sweep asks for. Speeds in rad/s.
struct LiftOffSweepSettings {
  double low_rad_s = 0.0;        // range of the search; the low end must not lift off,
  double high_rad_s = 0.0;       // the high end must
  double tolerance_rad_s = 0.0;  // stop when the bracket is at most this wide (> 0)
  double revolutions = 2.0;      // cam revolutions per run
};

// Refuses (std::invalid_argument, naming the option) a range that is not 0 < low < high,
// a tolerance that is not > 0, or fewer than 1 revolution.
void validate(const LiftOffSweepSettings& settings);

// The range when none is given: 0.5x..1.5x the kinetostatic lift-off speed of the same
// follower (the flexible one's overshoot puts it below 1x; 0.5x is far below any measured
// case). Throws std::invalid_argument when there is no finite, positive kinetostatic speed
// to scale (then the range must be given).
LiftOffSweepSettings default_sweep_range(const models::cam::LiftOffSpeed& kinetostatic, double tolerance_rad_s,
                                         double revolutions);

// One run at one speed.
struct LiftOffRun {
  double speed_rad_s = 0.0;
  int lift_offs = 0;                             // lift_off events of the follower in the run
  int landings = 0;
  std::optional<double> first_lift_off_angle_deg;  // cam angle of the first lift-off, [0, 360)
  std::optional<double> first_lift_off_t_s;
  double wall_time_s = 0.0;                      // the whole run: processes, DDS, reference
  std::string run_dir;                           // where its files are
  bool lifted_off() const { return lift_offs > 0; }
};

// The events of the follower participant `follower` in a `mechsim launch` summary
// (key `events`: objects with `node`, `kind`, `t_s`, `angle_deg`). Throws
// std::runtime_error when the summary says the run failed or has no events list.
LiftOffRun lift_off_run_from_summary(const nlohmann::json& summary, const std::string& follower, double speed_rad_s,
                                     double wall_time_s);

enum class LiftOffOutcome {
  found,                       // no lift-off at `low`, lift-off at `high`, high - low <= tolerance
  lifts_off_at_range_low,      // lifts off already at the low end: the speed is below the range
  no_lift_off_at_range_high,   // does not lift off at the high end: the speed is above the range
};
const char* outcome_name(LiftOffOutcome o);

struct LiftOffSearch {
  LiftOffOutcome outcome = LiftOffOutcome::found;
  // The final bracket: the highest speed run without lift-off and the lowest run with it.
  // Only `high` exists for lifts_off_at_range_low, only `low` for no_lift_off_at_range_high.
  std::optional<double> low_rad_s, high_rad_s;
  std::vector<LiftOffRun> runs;  // in the order they were run
};

// Bisection: runs the low end, then the high end, then halves the bracket [no lift-off,
// lift-off] until it is at most `tolerance_rad_s` wide. Stops early when an end of the range
// contradicts it. Assumes lift-off is monotone in speed; if it is not, the bracket still
// holds a transition (a run without lift-off below one with it), which is what is reported.
// `run` is called once per speed; `on_run` (optional) after each, for progress.
LiftOffSearch find_lift_off_speed(const LiftOffSweepSettings& settings,
                                  const std::function<LiftOffRun(double speed_rad_s)>& run,
                                  const std::function<void(const LiftOffRun&)>& on_run = {});

// The most runs `find_lift_off_speed` makes for these settings: 2 + ceil(log2(range/tol)).
int max_sweep_runs(const LiftOffSweepSettings& settings);

// The scene overrides of one run at `speed_rad_s`: the cam's constant speed (params.speed, or
// params.drive.speed where the scene gives it there) and the end time, `revolutions`
// revolutions after the start rounded up to whole macro steps. Refuses (config::ConfigError
// naming the key) a follower that is not `model: flexible` (a rigid one never lifts off) and a
// cam with a torque drive (the sweep, like the kinetostatic analysis, is at constant speed).
std::vector<std::string> lift_off_run_overrides(const config::Scene& scene, const RollerCase& roller,
                                                double speed_rad_s, double revolutions);

// The `lift_off_sweep` section of the report and the keys beside `lift_off_speed_rpm`
// (`lift_off_speed_simulated_rpm`, `lift_off_simulated_angle_deg`), added to `report`.
// `follower` is the analysed follower's parameters (for the kinetostatic speed with and
// without its functional loads).
void add_lift_off_sweep_json(nlohmann::json& report, const LiftOffSweepSettings& settings, const LiftOffSearch& search,
                             const models::cam::MotionLaw& law, const models::follower::FollowerParams& follower,
                             const std::string& follower_participant, double total_wall_time_s);

// Console lines: one per run ("lift-off sweep: run 3/10 at 106.52 rpm (11.15 rad/s): lift-off
// (10x, first at 49.8 deg)  0.8 s") and the result with the kinetostatic speed beside it.
std::string lift_off_run_line(const LiftOffRun& run, int index, int max_runs);
std::vector<std::string> lift_off_sweep_lines(const LiftOffSearch& search, const LiftOffSweepSettings& settings,
                                              const models::cam::LiftOffSpeed& kinetostatic, bool follower_has_loads);

}  // namespace mechsim::tools::cam_design
