// `mechsim cam-design SCENE`: the cam design report of spec cam.md §7 (docs/cam-design.md).
#include <cstdio>
#include <memory>

#include "cam_design_export.h"
#include "cam_design_json.h"
#include "cam_design_plots.h"
#include "cam_design_report.h"
#include "commands.h"
#include "json_io.h"
#include "mechsim/config/scene.h"

namespace mechsim::tools {

namespace {

struct CamDesignOptions {
  SceneArgs scene;
  std::string json_path, plots_dir, contour_csv, dxf;
  bool jump_speed = false;
};

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
  cmd->callback([opt, &exit_code] {
    namespace cd = cam_design;
    const std::vector<std::string> overrides = opt->scene.overrides();
    cd::CamDesignResult result;
    try {
      result = cd::analyse_scene(config::load_scene(opt->scene.scene, overrides), overrides);
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
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
