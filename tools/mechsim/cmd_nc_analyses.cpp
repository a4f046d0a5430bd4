// `mechsim motor-bode SCENE` (the motor-tacho frequency response of spec nc_slide.md §1) and
// `mechsim slide-modes SCENE` (the torsional eigenfrequencies of the slide drive train,
// §2): docs/nc-analyses.md. Both share one command shape: analyse, print, JSON, plots.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "json_io.h"
#include "mechsim/config/scene.h"
#include "motor_bode.h"
#include "nc_json.h"
#include "nc_plots.h"
#include "slide_modes.h"

namespace mechsim::tools {

namespace {

namespace nca = nc_analyses;

struct AnalysisOptions {
  SceneArgs scene;
  std::string json_path, plots_dir;
};

// Registers one NC analysis command; `analyse` runs it, `summary`, `to_json` and `figures`
// present its result.
template <typename Result, typename Analyse, typename Summary, typename ToJson, typename Figures>
void add_nc_analysis_command(CLI::App& app, int& exit_code, const std::string& name, const std::string& help,
                             Analyse analyse, Summary summary, ToJson to_json, Figures figures) {
  auto* cmd = app.add_subcommand(name, help);
  auto opt = std::make_shared<AnalysisOptions>();
  add_scene_args(cmd, opt->scene);
  cmd->add_option("--json", opt->json_path, "write the results (JSON) to this file");
  cmd->add_option("--plots", opt->plots_dir, "write the PNG plots into this directory");
  cmd->callback([=, &exit_code] {
    const std::vector<std::string> overrides = opt->scene.overrides();
    Result result;
    try {
      result = analyse(config::load_scene(opt->scene.scene, overrides), overrides);
    } catch (const config::ConfigError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      exit_code = 2;
      return;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim %s: %s\n", name.c_str(), e.what());
      exit_code = 1;
      return;
    }
    try {
      for (const auto& line : summary(result)) std::printf("%s\n", line.c_str());
      nlohmann::json report = to_json(result);
      nlohmann::json files = nlohmann::json::object();
      if (!opt->plots_dir.empty()) {
        const nca::PlotOutcome plots = nca::write_figures(opt->plots_dir, figures(result));
        files["plots"] = plots.files;
        // Plots are never fatal (gnuplot may be missing): say so and carry on.
        for (const auto& why : plots.problems) std::fprintf(stderr, "mechsim %s: no plot: %s\n", name.c_str(), why.c_str());
        if (!plots.problems.empty()) files["plot_problems"] = plots.problems;
      }
      report["files"] = files;
      if (!opt->json_path.empty()) write_json_file(opt->json_path, report);
      exit_code = 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim %s: %s\n", name.c_str(), e.what());
      exit_code = 1;
    }
  });
}

}  // namespace

void add_motor_bode_command(CLI::App& app, int& exit_code) {
  add_nc_analysis_command<nca::MotorBodeResult>(
      app, exit_code, "motor-bode",
      "Motor-tacho frequency response U_T/U_a of a scene (spec nc_slide.md §1): transfer function, poles, DC gain, "
      "corner, resonance, the report's approximations, shaft-damping and load-inertia variants; Bode plots as PNG",
      [](const config::Scene& s, const std::vector<std::string>& o) { return nca::analyse_motor_bode(s, o); },
      [](const nca::MotorBodeResult& r) { return nca::motor_bode_summary(r); },
      [](const nca::MotorBodeResult& r) { return nca::motor_bode_json(r); },
      [](const nca::MotorBodeResult& r) { return nca::motor_bode_figures(r); });
}

void add_slide_modes_command(CLI::App& app, int& exit_code) {
  add_nc_analysis_command<nca::SlideModesResult>(
      app, exit_code, "slide-modes",
      "Torsional eigenfrequencies of the slide drive train of a scene (spec nc_slide.md §2): models 1-3, the "
      "convergence of model 3 (Rayleigh-Ritz and FE), f0 against slide position and spindle diameter; PNG plots",
      [](const config::Scene& s, const std::vector<std::string>& o) { return nca::analyse_slide_modes(s, o); },
      [](const nca::SlideModesResult& r) { return nca::slide_modes_summary(r); },
      [](const nca::SlideModesResult& r) { return nca::slide_modes_json(r); },
      [](const nca::SlideModesResult& r) { return nca::slide_modes_figures(r); });
}

}  // namespace mechsim::tools
