// `mechsim cvt-map SCENE`: operating maps of the push-belt CVT over ratio setting, input
// torque and input speed (spec cvt.md §6.3; docs/cvt.md).
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.h"
#include "cvt_map.h"
#include "json_io.h"
#include "mechsim/config/scene.h"

namespace mechsim::tools {

namespace {

struct CvtMapOptions {
  SceneArgs scene;
  std::string json_path, plots_dir;
  int points = 0, s_points = 0, torque_points = 0, speed_points = 0;
};

}  // namespace

void add_cvt_map_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "cvt-map",
      "Operating maps of the push-belt CVT of a scene (spec cvt.md §6.3): input torque T_1, clamping force, belt and "
      "system efficiency, the four contact stresses and the slip margin over ratio setting x input torque x input "
      "speed (default: the thesis's 5 x 5 x 5 grid); JSON arrays with their axes, PNG maps");
  auto opt = std::make_shared<CvtMapOptions>();
  add_scene_args(cmd, opt->scene);
  cmd->add_option("--json", opt->json_path, "write the maps (JSON) to this file");
  cmd->add_option("--plots", opt->plots_dir, "write the PNG maps into this directory");
  cmd->add_option("--points", opt->points, "points on every axis (resampled evenly between its first and last value)")
      ->check(CLI::Range(1, 201));
  cmd->add_option("--s-points", opt->s_points, "points on the ratio-setting axis")->check(CLI::Range(1, 201));
  cmd->add_option("--torque-points", opt->torque_points, "points on the torque axis")->check(CLI::Range(1, 201));
  cmd->add_option("--speed-points", opt->speed_points, "points on the speed axis")->check(CLI::Range(1, 201));
  cmd->callback([opt, &exit_code] {
    namespace cm = cvt_map;
    const std::vector<std::string> overrides = opt->scene.overrides();
    auto pick = [&](int specific) -> std::optional<int> {
      if (specific > 0) return specific;
      if (opt->points > 0) return opt->points;
      return std::nullopt;
    };
    cm::GridOptions grid{pick(opt->s_points), pick(opt->torque_points), pick(opt->speed_points)};
    cm::CvtMapResult result;
    try {
      result = cm::analyse_scene(config::load_scene(opt->scene.scene, overrides), overrides, grid);
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
      return;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim cvt-map: %s\n", e.what());
      exit_code = 1;
      return;
    }
    try {
      for (const auto& line : cm::summary_lines(result)) std::printf("%s\n", line.c_str());
      nlohmann::json report = cm::report_json(result);
      nlohmann::json files = nlohmann::json::object();
      if (!opt->plots_dir.empty()) {
        const cm::PlotOutcome plots = cm::write_plots(opt->plots_dir, result);
        files["plots"] = plots.files;
        // Plots are never fatal (gnuplot may be missing): say so and carry on.
        for (const auto& why : plots.problems) std::fprintf(stderr, "mechsim cvt-map: no plot: %s\n", why.c_str());
        if (!plots.problems.empty()) files["plot_problems"] = plots.problems;
      }
      report["files"] = files;
      if (!opt->json_path.empty()) write_json_file(opt->json_path, report);
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim cvt-map: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace mechsim::tools
