// `mechsim cam-design SCENE`: the cam design report of spec cam.md §7 (docs/cam-design.md),
// optionally with the flexible follower's lift-off speed from distributed runs.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>

#include "cam_design_export.h"
#include "cam_design_json.h"
#include "cam_design_plots.h"
#include "cam_design_report.h"
#include "cam_lift_off_launch.h"
#include "cam_lift_off_sweep.h"
#include "commands.h"
#include "json_io.h"
#include "mechsim/config/scene.h"
#include "mechsim/config/units.h"
#include "mechsim/models/constants.h"

namespace mechsim::tools {

namespace {

struct CamDesignOptions {
  SceneArgs scene;
  std::string json_path, plots_dir, contour_csv, dxf;
  bool jump_speed = false;
  // --lift-off-sweep
  bool sweep = false;
  std::string sweep_range, sweep_tol = "0.5 rpm", runs_dir = "runs";
  double sweep_revolutions = 2.0;
};

// A speed with its unit ("60 rpm", "6.5 rad/s"): a bare number would be ambiguous here.
double parse_speed(const std::string& option, const std::string& text) {
  config::Quantity q;
  try {
    q = config::parse_quantity(text);
  } catch (const config::UnitError& e) {
    throw std::invalid_argument(option + ": " + e.what());
  }
  if (!q.has_unit || q.dimension != config::dim::angular_velocity)
    throw std::invalid_argument(option + ": expected a speed with its unit, e.g. '60 rpm', got '" + text + "'");
  return q.value_si;
}

cam_design::LiftOffSweepSettings sweep_settings(const CamDesignOptions& o, const models::cam::LiftOffSpeed& kinetostatic) {
  const double tol = parse_speed("--sweep-tol", o.sweep_tol);
  if (o.sweep_range.empty()) return cam_design::default_sweep_range(kinetostatic, tol, o.sweep_revolutions);
  const auto dots = o.sweep_range.find("..");
  if (dots == std::string::npos)
    throw std::invalid_argument("--sweep-range: expected LOW..HIGH, e.g. '60 rpm..160 rpm', got '" + o.sweep_range + "'");
  cam_design::LiftOffSweepSettings s{parse_speed("--sweep-range", o.sweep_range.substr(0, dots)),
                                     parse_speed("--sweep-range", o.sweep_range.substr(dots + 2)), tol,
                                     o.sweep_revolutions};
  cam_design::validate(s);
  return s;
}

// <runs-dir>/<scene>-lift-off-<UTC time>-<pid>: the sweep's run folders, summaries and logs.
std::string sweep_folder(const std::string& runs_dir, const std::string& scene) {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", std::gmtime(&now));
  return (std::filesystem::path(runs_dir) / (scene + "-lift-off-" + stamp + "-" + std::to_string(::getpid()))).string();
}

// A lift-off sweep, checked before anything runs.
struct SweepPlan {
  config::Scene scene;
  cam_design::LiftOffSweepSettings settings;
  cam_design::LiftOffLaunchOptions launch;
};

// Throws config::ConfigError for a scene that cannot be swept (flat-faced analysis, rigid
// follower, torque drive) and std::invalid_argument for bad sweep options.
SweepPlan plan_sweep(const CamDesignOptions& o, const config::Scene& scene, const cam_design::CamDesignResult& result) {
  if (!result.roller)
    throw config::ConfigError(result.scene_file, "design.follower",
                              "expected roller for --lift-off-sweep: the sweep runs the scene's cam_shaft and "
                              "follower participants, the flat-faced follower is an analysis only");
  SweepPlan plan{scene, sweep_settings(o, result.roller->report.lift_off), {}};
  cam_design::lift_off_run_overrides(scene, result.roller->input_case, plan.settings.low_rad_s, plan.settings.revolutions);
  plan.launch = {o.scene.scene, o.scene.overrides(), sweep_folder(o.runs_dir, scene.name), ""};
  return plan;
}

// Runs the sweep with a progress line per run and adds its keys to `report`.
void run_sweep(const SweepPlan& plan, const cam_design::CamDesignResult& result, nlohmann::json& report) {
  namespace cd = cam_design;
  using models::rpm;
  const cd::RollerCase& roller = result.roller->input_case;
  const cd::LiftOffSweepSettings& settings = plan.settings;
  const int max_runs = cd::max_sweep_runs(settings);
  std::printf("\nlift-off sweep of '%s' ('%s'): %.2f..%.2f rpm to %.3g rpm, %g revolutions per run, at most %d runs, "
              "folder %s\n",
              plan.scene.name.c_str(), roller.follower_participant.c_str(), settings.low_rad_s / rpm,
              settings.high_rad_s / rpm, settings.tolerance_rad_s / rpm, settings.revolutions, max_runs,
              plan.launch.sweep_dir.c_str());
  std::fflush(stdout);
  int index = 0;
  const auto started = std::chrono::steady_clock::now();
  const cd::LiftOffSearch search = cd::find_lift_off_speed(
      settings,
      [&](double speed) {
        return cd::launch_lift_off_run(plan.scene, roller, plan.launch, speed, settings.revolutions, ++index);
      },
      [&](const cd::LiftOffRun& run) {
        std::printf("%s\n", cd::lift_off_run_line(run, index, max_runs).c_str());
        std::fflush(stdout);
      });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  for (const auto& line :
       cd::lift_off_sweep_lines(search, settings, result.roller->report.lift_off, !roller.input.follower.loads.empty()))
    std::printf("%s\n", line.c_str());
  cd::add_lift_off_sweep_json(report, settings, search, models::cam::MotionLaw(roller.input.segments),
                              roller.input.follower, roller.follower_participant, wall);
}

}  // namespace

void add_cam_design_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "cam-design",
      "Cam design report of a scene (spec cam.md §7): pressure angle, curvature, forces, spring, power, flywheel, "
      "flexible follower; contour as CSV/DXF, PNG plots");
  auto opt = std::make_shared<CamDesignOptions>();
  add_scene_args(cmd, opt->scene);
  cmd->add_option("--json", opt->json_path, "write the report (JSON) to this file");
  cmd->add_option("--plots", opt->plots_dir, "write the PNG plots into this directory");
  cmd->add_option("--contour-csv", opt->contour_csv, "write the cam contour (theta, pitch and real contour in mm) as CSV");
  cmd->add_option("--dxf", opt->dxf, "write the real cam contour as an ASCII DXF (R12, mm)");
  cmd->add_flag("--jump-speed", opt->jump_speed, "print the kinetostatic lift-off speed prominently");
  cmd->add_flag("--lift-off-sweep", opt->sweep,
                "also find the flexible follower's actual lift-off speed: distributed runs (mechsim launch) of the "
                "scene at constant cam speeds, bisected to the lowest speed with a lift-off event (JSON "
                "lift_off_speed_simulated_rpm, lift_off_sweep); the follower must be model: flexible");
  cmd->add_option("--sweep-range", opt->sweep_range,
                  "speeds to search, LOW..HIGH with units, e.g. '50 rpm..110 rpm' (default 0.5x..1.5x the "
                  "kinetostatic lift-off speed); LOW must not lift off, HIGH must");
  cmd->add_option("--sweep-tol", opt->sweep_tol, "stop when the bracket is this narrow")->capture_default_str();
  cmd->add_option("--sweep-revolutions", opt->sweep_revolutions, "cam revolutions per run")->capture_default_str();
  cmd->add_option("--runs-dir", opt->runs_dir,
                  "parent folder of the sweep's folder (<scene>-lift-off-<time>-<pid>: run folders, summaries, logs)")
      ->capture_default_str();
  cmd->callback([opt, &exit_code] {
    namespace cd = cam_design;
    const std::vector<std::string> overrides = opt->scene.overrides();
    cd::CamDesignResult result;
    std::optional<SweepPlan> sweep;
    try {
      const config::Scene scene = config::load_scene(opt->scene.scene, overrides);
      result = cd::analyse_scene(scene, overrides);
      if (opt->sweep) sweep = plan_sweep(*opt, scene, result);
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
      return;
    } catch (const std::invalid_argument& e) {  // the sweep's options
      std::fprintf(stderr, "mechsim cam-design: %s\n", e.what());
      exit_code = 2;
      return;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim cam-design: %s\n", e.what());
      exit_code = 1;
      return;
    }
    try {
      for (const auto& line : cd::summary_lines(result)) std::printf("%s\n", line.c_str());
      if (opt->jump_speed) {
        const auto& lift_off = result.roller ? result.roller->report.lift_off : result.flat_face->lift_off;
        std::printf("\n*** %s ***\n", cd::lift_off_line(lift_off).c_str());
      }
      nlohmann::json report = cd::report_json(result);
      if (sweep) run_sweep(*sweep, result, report);
      nlohmann::json files = nlohmann::json::object();
      if (!opt->contour_csv.empty()) {
        cd::write_contour_csv(opt->contour_csv, result);
        files["contour_csv"] = opt->contour_csv;
      }
      if (!opt->dxf.empty()) {
        cd::write_contour_dxf(opt->dxf, result);
        files["dxf"] = opt->dxf;
      }
      if (!opt->plots_dir.empty()) {
        const cd::PlotOutcome plots = cd::write_plots(opt->plots_dir, result);
        files["plots"] = plots.files;
        // Plots are never fatal (gnuplot may be missing): say so and carry on.
        for (const auto& why : plots.problems) std::fprintf(stderr, "mechsim cam-design: no plot: %s\n", why.c_str());
        if (!plots.problems.empty()) files["plot_problems"] = plots.problems;
      }
      report["files"] = files;
      if (!opt->json_path.empty()) write_json_file(opt->json_path, report);
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim cam-design: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace mechsim::tools
