// `mechsim slide-modes SCENE`: the torsional eigenfrequencies of the slide drive train of
// spec nc_slide.md §2 (docs/nc-analyses.md).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "json_io.h"
#include "mechsim/config/scene.h"
#include "nc_json.h"
#include "nc_plots.h"
#include "slide_modes.h"

namespace mechsim::tools {

namespace {

struct SlideModesOptions {
  SceneArgs scene;
  std::string json_path, plots_dir;
};

// SceneArgs' overrides plus the design-section ones, which it would misread as a participant.
std::vector<std::string> nc_overrides(const SceneArgs& args) {
  const nc_analyses::SplitOverrides split = nc_analyses::split_design_overrides(args.sets);
  SceneArgs others = args;
  others.sets = split.others;
  std::vector<std::string> out = others.overrides();
  out.insert(out.end(), split.design.begin(), split.design.end());
  return out;
}

}  // namespace

void add_slide_modes_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "slide-modes",
      "Torsional eigenfrequencies of the slide drive train of a scene (spec nc_slide.md §2): models 1-3, the "
      "convergence of model 3 (Rayleigh-Ritz and FE), f0 against slide position and spindle diameter; PNG plots");
  auto opt = std::make_shared<SlideModesOptions>();
  add_scene_args(cmd, opt->scene);
  cmd->add_option("--json", opt->json_path, "write the results (JSON) to this file");
  cmd->add_option("--plots", opt->plots_dir, "write the PNG plots into this directory");
  cmd->callback([opt, &exit_code] {
    namespace nca = nc_analyses;
    const std::vector<std::string> overrides = nc_overrides(opt->scene);
    nca::SlideModesResult result;
    try {
      result = nca::analyse_slide_modes(config::load_scene(opt->scene.scene, overrides), overrides);
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
      return;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim slide-modes: %s\n", e.what());
      exit_code = 1;
      return;
    }
    try {
      for (const auto& line : nca::slide_modes_summary(result)) std::printf("%s\n", line.c_str());
      nlohmann::json report = nca::slide_modes_json(result);
      nlohmann::json files = nlohmann::json::object();
      if (!opt->plots_dir.empty()) {
        const nca::PlotOutcome plots = nca::write_figures(opt->plots_dir, nca::slide_modes_figures(result));
        files["plots"] = plots.files;
        // Plots are never fatal (gnuplot may be missing): say so and carry on.
        for (const auto& why : plots.problems) std::fprintf(stderr, "mechsim slide-modes: no plot: %s\n", why.c_str());
        if (!plots.problems.empty()) files["plot_problems"] = plots.problems;
      }
      report["files"] = files;
      if (!opt->json_path.empty()) write_json_file(opt->json_path, report);
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim slide-modes: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace mechsim::tools
