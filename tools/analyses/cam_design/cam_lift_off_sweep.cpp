#include "cam_lift_off_sweep.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "cam_design_json.h"
#include "json_io.h"
#include "mechsim/catalog/node_params.h"
#include "mechsim/models/constants.h"
#include "text_format.h"

namespace mechsim::tools::cam_design {

namespace cam = models::cam;
using nlohmann::json;

namespace {

using models::pi;
using models::degree;
using models::rpm;

json optional_number(const std::optional<double>& v) { return v ? finite_or_null(*v) : json(nullptr); }
json rpm_or_null(const std::optional<double>& rad_s) { return rad_s ? finite_or_null(*rad_s / rpm) : json(nullptr); }

// The run of the search at the bracket's lift-off end (its first lift-off is "the" angle).
const LiftOffRun* run_at(const LiftOffSearch& s, const std::optional<double>& speed) {
  if (!speed) return nullptr;
  for (const auto& r : s.runs)
    if (r.speed_rad_s == *speed) return &r;
  return nullptr;
}

}  // namespace

void validate(const LiftOffSweepSettings& s) {
  if (!(s.low_rad_s > 0.0 && s.high_rad_s > s.low_rad_s && std::isfinite(s.high_rad_s)))
    throw std::invalid_argument(fmt("--sweep-range: expected 0 < low < high, got %g rpm..%g rpm", s.low_rad_s / rpm,
                                       s.high_rad_s / rpm));
  if (!(s.tolerance_rad_s > 0.0 && std::isfinite(s.tolerance_rad_s)))
    throw std::invalid_argument(fmt("--sweep-tol: expected a speed > 0, got %g rpm", s.tolerance_rad_s / rpm));
  if (!(s.revolutions >= 1.0 && std::isfinite(s.revolutions)))
    throw std::invalid_argument(fmt("--sweep-revolutions: expected at least 1, got %g", s.revolutions));
}

LiftOffSweepSettings default_sweep_range(const cam::LiftOffSpeed& kinetostatic, double tolerance_rad_s,
                                         double revolutions) {
  const double w = kinetostatic.speed_rad_s;
  if (!(std::isfinite(w) && w > 0.0))
    throw std::invalid_argument(
        std::string("--sweep-range is needed: the default range is 0.5x..1.5x the kinetostatic lift-off speed, and ") +
        (w == 0.0 ? "the static forces alone already open the contact" : "the rigid follower never lifts off"));
  return {0.5 * w, 1.5 * w, tolerance_rad_s, revolutions};
}

LiftOffRun lift_off_run_from_summary(const json& summary, const std::string& follower, double speed_rad_s,
                                     double wall_time_s) {
  if (summary.value("status", "") != "ok") {
    std::string why = "the run summary says status '" + summary.value("status", std::string("?")) + "'";
    if (summary.contains("failure")) why += ": " + summary["failure"].value("reason", std::string());
    throw std::runtime_error(why);
  }
  if (!summary.contains("events") || !summary["events"].is_array())
    throw std::runtime_error("the run summary has no 'events' list");
  LiftOffRun r;
  r.speed_rad_s = speed_rad_s;
  r.wall_time_s = wall_time_s;
  r.run_dir = summary.value("run_dir", std::string());
  for (const auto& e : summary["events"]) {
    if (e.value("node", std::string()) != follower) continue;
    const std::string kind = e.value("kind", std::string());
    if (kind == "landing") ++r.landings;
    if (kind != "lift_off") continue;
    ++r.lift_offs;
    const double t = e.value("t_s", std::numeric_limits<double>::infinity());
    if (!r.first_lift_off_t_s || t < *r.first_lift_off_t_s) {
      r.first_lift_off_t_s = t;
      if (e.contains("angle_deg") && e["angle_deg"].is_number())
        r.first_lift_off_angle_deg = e["angle_deg"].get<double>();
      else
        r.first_lift_off_angle_deg.reset();
    }
  }
  return r;
}

const char* outcome_name(LiftOffOutcome o) {
  switch (o) {
    case LiftOffOutcome::found: return "found";
    case LiftOffOutcome::lifts_off_at_range_low: return "lifts_off_at_range_low";
    case LiftOffOutcome::no_lift_off_at_range_high: return "no_lift_off_at_range_high";
  }
  return "?";
}

LiftOffSearch find_lift_off_speed(const LiftOffSweepSettings& settings, const std::function<LiftOffRun(double)>& run,
                                  const std::function<void(const LiftOffRun&)>& on_run) {
  validate(settings);
  LiftOffSearch s;
  auto lifts_off = [&](double speed) {
    LiftOffRun r = run(speed);
    r.speed_rad_s = speed;  // the bracket is kept in the speeds asked for
    s.runs.push_back(r);
    if (on_run) on_run(s.runs.back());
    return s.runs.back().lifted_off();
  };
  double low = settings.low_rad_s, high = settings.high_rad_s;
  if (lifts_off(low)) {
    s.outcome = LiftOffOutcome::lifts_off_at_range_low;
    s.high_rad_s = low;
    return s;
  }
  if (!lifts_off(high)) {
    s.outcome = LiftOffOutcome::no_lift_off_at_range_high;
    s.low_rad_s = high;
    return s;
  }
  while (high - low > settings.tolerance_rad_s) {
    const double mid = 0.5 * (low + high);
    (lifts_off(mid) ? high : low) = mid;
  }
  s.outcome = LiftOffOutcome::found;
  s.low_rad_s = low;
  s.high_rad_s = high;
  return s;
}

int max_sweep_runs(const LiftOffSweepSettings& settings) {
  validate(settings);
  int halvings = 0;
  for (double width = settings.high_rad_s - settings.low_rad_s; width > settings.tolerance_rad_s; width *= 0.5)
    ++halvings;  // the same halving as the search, so the count is exact
  return 2 + halvings;
}

std::vector<std::string> lift_off_run_overrides(const config::Scene& scene, const RollerCase& roller,
                                                double speed_rad_s, double revolutions) {
  const config::ParticipantSpec* follower = scene.find_participant(roller.follower_participant);
  const config::ParticipantSpec* cam_spec = scene.find_participant(roller.cam_participant);
  if (!follower || !cam_spec) throw std::logic_error("lift-off sweep: the analysed participants are not in the scene");
  if (cosim::parse_follower_params(follower->params).model != "flexible") {
    const std::string why =
        "expected 'flexible' for the lift-off sweep: a rigid follower never leaves the cam (its lift-off is the "
        "kinetostatic one, lift_off_speed_rpm); config/scenes/cam_lift_off.yaml has a flexible follower";
    if (follower->params.has("model")) follower->params.child("model").fail(why);
    throw config::ConfigError(scene.file, follower->key_path + ".params.model", "missing key (" + why + ")");
  }
  const cam::CamShaftParams shaft = cosim::parse_cam_shaft_params(cam_spec->params);
  if (shaft.drive.is_torque_source())
    cam_spec->params.child("drive").fail(
        "expected a constant-speed drive for the lift-off sweep: it runs the cam at fixed speeds, as the "
        "kinetostatic analysis assumes");
  const bool speed_in_drive = cam_spec->params.has("drive") && cam_spec->params.child("drive").has("speed");
  const std::string speed_key =
      cam_spec->key_path + ".params." + (speed_in_drive ? std::string("drive.speed") : std::string("speed"));
  const config::TimeSpec& time = scene.time;
  // Whole macro steps (the scene refuses anything else); the last bit of a revolution is
  // never cut off.
  const double steps = std::ceil(revolutions * 2.0 * pi / speed_rad_s / time.step - 1e-9);
  return {fmt("%s=%.17g rad/s", speed_key.c_str(), speed_rad_s),
          fmt("time.end=%.17g s", time.start + steps * time.step)};
}

void add_lift_off_sweep_json(json& report, const LiftOffSweepSettings& settings, const LiftOffSearch& search,
                             const cam::MotionLaw& law, const models::follower::FollowerParams& follower,
                             const std::string& follower_participant, double total_wall_time_s) {
  const cam::LiftOffSpeed with_loads = cam::kinetostatic_lift_off_speed(law, follower);
  auto no_loads_follower = follower;
  no_loads_follower.loads.clear();
  const cam::LiftOffSpeed no_loads = cam::kinetostatic_lift_off_speed(law, no_loads_follower);

  const LiftOffRun* first = run_at(search, search.high_rad_s);
  const bool found = search.outcome == LiftOffOutcome::found;
  json runs = json::array();
  for (const auto& r : search.runs)
    runs.push_back({{"speed_rpm", r.speed_rad_s / rpm},
                    {"speed_rad_s", r.speed_rad_s},
                    {"lifted_off", r.lifted_off()},
                    {"lift_off_count", r.lift_offs},
                    {"landing_count", r.landings},
                    {"first_lift_off_angle_deg", optional_number(r.first_lift_off_angle_deg)},
                    {"first_lift_off_t_s", optional_number(r.first_lift_off_t_s)},
                    {"wall_time_s", r.wall_time_s},
                    {"run_dir", r.run_dir}});
  const double simulated = found ? *search.high_rad_s : std::numeric_limits<double>::quiet_NaN();
  report["lift_off_speed_simulated_rpm"] = finite_or_null(simulated / rpm);
  report["lift_off_simulated_angle_deg"] =
      first && first->first_lift_off_angle_deg ? json(*first->first_lift_off_angle_deg) : json(nullptr);
  report["lift_off_sweep"] = {
      {"method", "bisection over distributed runs (mechsim launch) of the scene at constant cam speeds"},
      {"follower", follower_participant},
      {"outcome", outcome_name(search.outcome)},
      {"range_rpm", {settings.low_rad_s / rpm, settings.high_rad_s / rpm}},
      {"tolerance_rpm", settings.tolerance_rad_s / rpm},
      {"revolutions_per_run", settings.revolutions},
      {"bracket_rpm", {rpm_or_null(search.low_rad_s), rpm_or_null(search.high_rad_s)}},
      {"bracket_width_rpm", found ? json((*search.high_rad_s - *search.low_rad_s) / rpm) : json(nullptr)},
      {"lift_off_speed_simulated_rpm", finite_or_null(simulated / rpm)},
      {"first_lift_off_angle_deg", report["lift_off_simulated_angle_deg"]},
      {"first_lift_off_t_s", first ? optional_number(first->first_lift_off_t_s) : json(nullptr)},
      {"follower_has_loads", !follower.loads.empty()},
      {"kinetostatic_lift_off_speed_rpm", finite_or_null(with_loads.speed_rad_s / rpm)},
      {"kinetostatic_lift_off_angle_deg",
       std::isfinite(with_loads.speed_rad_s) ? cycle_deg(with_loads.angle_rad) : json(nullptr)},
      {"kinetostatic_lift_off_speed_no_loads_rpm", finite_or_null(no_loads.speed_rad_s / rpm)},
      {"kinetostatic_lift_off_angle_no_loads_deg",
       std::isfinite(no_loads.speed_rad_s) ? cycle_deg(no_loads.angle_rad) : json(nullptr)},
      {"simulated_to_kinetostatic", found ? finite_or_null(simulated / with_loads.speed_rad_s) : json(nullptr)},
      {"run_count", search.runs.size()},
      {"runs", runs},
      {"wall_time_s", total_wall_time_s}};
}

std::string lift_off_run_line(const LiftOffRun& r, int index, int max_runs) {
  std::string what = "no lift-off";
  if (r.lifted_off())
    what = r.first_lift_off_angle_deg
               ? fmt("lift-off (%dx, first at %.1f deg)", r.lift_offs, *r.first_lift_off_angle_deg)
               : fmt("lift-off (%dx)", r.lift_offs);
  const int width = max_runs >= 10 ? 2 : 1;  // aligned columns
  return fmt("lift-off sweep: run %*d/%d at %7.2f rpm (%6.4g rad/s): %-31s %5.1f s", width, index, max_runs,
                r.speed_rad_s / rpm, r.speed_rad_s, what.c_str(), r.wall_time_s);
}

std::vector<std::string> lift_off_sweep_lines(const LiftOffSearch& s, const LiftOffSweepSettings& settings,
                                              const cam::LiftOffSpeed& kinetostatic, bool follower_has_loads) {
  std::vector<std::string> out;
  double wall = 0.0;
  for (const auto& r : s.runs) wall += r.wall_time_s;
  const LiftOffRun* first = run_at(s, s.high_rad_s);
  const std::string angle = first && first->first_lift_off_angle_deg
                                ? fmt(", first at %.1f deg", *first->first_lift_off_angle_deg)
                                : std::string();
  switch (s.outcome) {
    case LiftOffOutcome::found:
      out.push_back(fmt("lift-off speed (flexible follower, %zu distributed runs, %.0f s): %.2f rpm (%.4g rad/s)%s; "
                           "no lift-off at %.2f rpm (tolerance %.3g rpm)",
                           s.runs.size(), wall, *s.high_rad_s / rpm, *s.high_rad_s, angle.c_str(), *s.low_rad_s / rpm,
                           settings.tolerance_rad_s / rpm));
      if (std::isfinite(kinetostatic.speed_rad_s) && kinetostatic.speed_rad_s > 0.0)
        out.push_back(fmt("  beside the kinetostatic one (rigid follower, same mass, spring and loads): %.2f rpm at %.1f deg; "
                             "simulated/kinetostatic = %.3f",
                             kinetostatic.speed_rad_s / rpm, std::fmod(kinetostatic.angle_rad / degree + 360.0, 360.0),
                             *s.high_rad_s / kinetostatic.speed_rad_s));
      break;
    case LiftOffOutcome::lifts_off_at_range_low:
      out.push_back(fmt("lift-off speed (flexible follower): below %.2f rpm, the low end of the range: it lifts off "
                           "there already%s (lower --sweep-range%s)",
                           settings.low_rad_s / rpm, angle.c_str(),
                           follower_has_loads ? "; functional load steps can open the contact at any speed, "
                                                "config/scenes/cam_lift_off.yaml is the follower without them"
                                              : ""));
      break;
    case LiftOffOutcome::no_lift_off_at_range_high:
      out.push_back(fmt("lift-off speed (flexible follower): above %.2f rpm, the high end of the range: no lift-off "
                           "there (raise --sweep-range)",
                           settings.high_rad_s / rpm));
      break;
  }
  return out;
}

}  // namespace mechsim::tools::cam_design
