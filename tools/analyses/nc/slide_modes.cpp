#include "slide_modes.h"

#include <cmath>

#include "text_format.h"

namespace mechsim::tools::nc_analyses {

namespace nc = models::nc;

namespace {

struct Model3 {
  const SlideModesSettings& settings;
  double ritz_hz(const nc::SlideDriveData& data, double x, int shapes) const {
    return nc::continuous_shaft_frequency_hz(data, x, shapes, settings.lump_coupling_inertia);
  }
  double fe_hz(const nc::SlideDriveData& data, double x, int elements) const {
    return nc::continuous_shaft_fe_frequency_hz(data, x, elements, settings.lump_coupling_inertia);
  }
  double ritz_hz(const nc::SlideDriveData& data, double x) const { return ritz_hz(data, x, settings.ritz_shapes); }
  double converged_hz(const nc::SlideDriveData& data, double x) const {
    return fe_hz(data, x, settings.sweep_fe_elements);
  }
};

}  // namespace

SlideModesResult analyse_slide_modes(const config::Scene& scene, std::vector<std::string> overrides) {
  SlideModesResult r;
  r.scene_name = scene.name;
  r.scene_file = scene.file;
  r.overrides = std::move(overrides);
  const NcDesignSettings settings = parse_nc_design_settings(scene.design);
  r.settings = settings.slide_modes;
  r.slide = slide_case_from_scene(scene, settings);
  motor_case_from_scene(scene, settings);  // unused here; parsed so that either command refuses bad motor data
  const nc::SlideDriveData& data = r.slide.data;
  const double length = data.spindle_length;
  r.slide_position = r.settings.slide_position.value_or(nc::mid_slide_position(data));
  if (r.slide_position > length)
    r.settings.slide_position_node->fail("expected a slide position on the spindle, at most its length (" +
                                         fmt("%g mm", length * 1e3) + ")");
  const Model3 model3{r.settings};

  r.model1_hz = nc::two_inertia_frequency_hz(data);
  r.model2 = nc::grounded_chain_frequencies_hz(data);
  r.model3_hz = model3.ritz_hz(data, r.slide_position);
  for (int n : r.settings.ritz_convergence) r.ritz_convergence.push_back({n, model3.ritz_hz(data, r.slide_position, n)});
  for (int n : r.settings.fe_convergence) r.fe_convergence.push_back({n, model3.fe_hz(data, r.slide_position, n)});
  r.model3_converged_hz = r.fe_convergence.back().frequency_hz;
  if (r.fe_convergence.size() >= 2) {
    // The lumped-mass chain converges as O(h²) (torsion_shaft.h).
    const ConvergencePoint& coarse = r.fe_convergence[r.fe_convergence.size() - 2];
    const ConvergencePoint& fine = r.fe_convergence.back();
    const double ratio = double(fine.count) / coarse.count;
    r.model3_extrapolated_hz = fine.frequency_hz + (fine.frequency_hz - coarse.frequency_hz) / (ratio * ratio - 1);
  }

  const int points = r.settings.position_points;
  for (int i = 0; i < points; ++i) {
    const double x = length * i / (points - 1);
    r.f0_vs_position.push_back({x, model3.ritz_hz(data, x), model3.converged_hz(data, x)});
    if (i == 0 || r.f0_vs_position.back().converged_hz > r.f0_max.converged_hz) r.f0_max = r.f0_vs_position.back();
  }
  const double equivalent_length = data.coupling_equivalent_length();
  const double node = (length - equivalent_length) / 2;
  if (!r.settings.lump_coupling_inertia && node >= 0 && node <= length)
    r.first_mode_node = {{node, std::sqrt(data.shear_modulus / data.density) / (2 * (equivalent_length + length))}};

  const int diameters = r.settings.diameter_points;
  for (int i = 0; i < diameters; ++i) {
    // Only the spindle changes: the coupling keeps its stand-in piece (spec §2, model 3).
    const nc::SlideDriveData d = nc::with_spindle_diameter(
        data, r.settings.diameter_from + (r.settings.diameter_to - r.settings.diameter_from) * i / (diameters - 1));
    r.f0_vs_diameter.push_back({d.spindle_diameter, nc::two_inertia_frequency_hz(d), nc::grounded_chain_frequencies_hz(d),
                                model3.ritz_hz(d, r.slide_position), model3.converged_hz(d, r.slide_position),
                                d.coupling_equivalent_length()});
  }
  return r;
}

std::vector<std::string> slide_modes_summary(const SlideModesResult& r) {
  std::vector<std::string> lines;
  lines.push_back("slide-modes: scene '" + r.scene_name + "', slide data from " +
                  (r.slide.source.where.empty() ? r.slide.source.kind : r.slide.source.where) + ", C_kopp from " +
                  (r.slide.coupling_stiffness_source.kind == "connection" ? r.slide.coupling_stiffness_source.where
                                                                          : r.slide.coupling_stiffness_source.kind));
  for (const auto& note : r.slide.notes) lines.push_back("  note: " + note);
  lines.push_back(fmt("  I_slide %.4g kg m^2, I_sp %.4g kg m^2, C_sp %.4g N m/rad", r.slide.data.slide_inertia(),
                      r.slide.data.spindle_inertia(), r.slide.data.spindle_stiffness()));
  lines.push_back(fmt("  model 1 (two inertias)      %.1f Hz", r.model1_hz));
  lines.push_back(fmt("  model 2 (grounded chain)    %.1f Hz, %.1f Hz", r.model2.first_hz, r.model2.second_hz));
  lines.push_back(fmt("  model 3 (continuous shaft)  %.1f Hz at x = %.0f mm", r.model3_hz, r.slide_position * 1e3) +
                  fmt(" with %.0f Ritz shapes; converged %.2f Hz", static_cast<double>(r.settings.ritz_shapes), r.model3_converged_hz));
  lines.push_back(fmt("  f0(x) highest               %.1f Hz at x = %.0f mm", r.f0_max.converged_hz,
                      r.f0_max.position * 1e3));
  if (r.first_mode_node)
    lines.push_back(fmt("  first-mode node             x = %.0f mm, f0 = %.1f Hz for any slide inertia",
                        r.first_mode_node->position * 1e3, r.first_mode_node->frequency_hz));
  const DiameterPoint& lo = r.f0_vs_diameter.front();
  const DiameterPoint& hi = r.f0_vs_diameter.back();
  lines.push_back(fmt("  f0 model 3 over d           %.1f Hz at %.0f mm", lo.model3_hz, lo.diameter * 1e3) +
                  fmt(" .. %.1f Hz at %.0f mm", hi.model3_hz, hi.diameter * 1e3));
  return lines;
}

}  // namespace mechsim::tools::nc_analyses
