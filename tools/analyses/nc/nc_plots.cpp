#include "nc_plots.h"

#include <algorithm>
#include <cmath>

#include "text_format.h"

namespace mechsim::tools::nc_analyses {

namespace {

// The plot library draws an opaque key in the top right corner: widen the y range upwards
// so that the curves stay below it (about 8 % of the plot height per key entry).
void leave_room_for_key(plot::Panel& panel) {
  double lo = INFINITY, hi = -INFINITY;
  int entries = static_cast<int>(panel.hlines.size());
  for (const auto& series : panel.series) {
    if (!series.label.empty()) ++entries;
    for (double y : series.y)
      if (std::isfinite(y) && (!panel.logy || y > 0)) lo = std::min(lo, y), hi = std::max(hi, y);
  }
  for (const auto& [y, label] : panel.hlines) lo = std::min(lo, y), hi = std::max(hi, y);
  if (!(hi > lo)) return;
  const double key_fraction = std::min(0.6, 0.05 + 0.08 * entries);
  if (panel.logy) {
    const double decades = std::log10(hi / lo);
    panel.yrange = {{lo / 2, hi * std::pow(10.0, decades * key_fraction / (1 - key_fraction)) * 2}};
  } else {
    const double margin = 0.03 * (hi - lo);
    panel.yrange = {{lo - margin, hi + margin + (hi - lo) * key_fraction / (1 - key_fraction)}};
  }
}

plot::Figure with_room_for_keys(plot::Figure figure) {
  for (auto& panel : figure.panels) leave_room_for_key(panel);
  figure.height_px_per_panel = 400;
  return figure;
}

struct LabelledAnalysis {
  std::string label;
  const MotorTachoAnalysis* analysis;
};

// Magnitude and phase of several parameter sets over a log frequency axis.
plot::Figure bode_figure(const std::string& title, const std::vector<LabelledAnalysis>& curves) {
  plot::Panel magnitude{.title = "Magnitude of U_T/U_a", .xlabel = "frequency [Hz]", .ylabel = "|G| [dB]", .logx = true};
  plot::Panel phase{.title = "Phase of U_T/U_a", .xlabel = "frequency [Hz]", .ylabel = "phase [deg]", .logx = true};
  for (const auto& [label, a] : curves) {
    magnitude.series.push_back({.label = label, .x = a->bode.frequency_hz, .y = a->bode.magnitude_db});
    phase.series.push_back({.label = label, .x = a->bode.frequency_hz, .y = a->bode.phase_deg});
  }
  return {.title = title, .panels = {magnitude, phase}};
}

plot::Figure nominal_bode(const MotorBodeResult& r) {
  const MotorTachoAnalysis& n = r.nominal;
  plot::Figure figure = bode_figure(
      "Motor-tacho U_T/U_a (scene " + r.scene_name + fmt("): DC gain %.3f, corner %.1f Hz", n.dc_gain, n.corner_hz) +
          (n.resonance ? fmt(", resonance %.0f Hz (%+.1f dB)", n.resonance->frequency_hz, n.resonance->peak_height_db)
                       : std::string()),
      {{"exact model", &n}});
  plot::Panel& magnitude = figure.panels[0];
  const double dc_db = 20 * std::log10(n.dc_gain);
  magnitude.hlines.push_back({dc_db, "DC gain"});
  magnitude.hlines.push_back({dc_db - 20 * std::log10(std::sqrt(2.0)), "-3 dB"});
  plot::Series marks{.label = "corner, resonance", .style = "points"};
  marks.x.push_back(n.corner_hz);
  marks.y.push_back(dc_db - 20 * std::log10(std::sqrt(2.0)));
  if (n.resonance) {
    marks.x.push_back(n.resonance->frequency_hz);
    marks.y.push_back(dc_db + n.resonance->peak_height_db);
  }
  magnitude.series.push_back(marks);
  return figure;
}

plot::Figure b3_variants_bode(const MotorBodeResult& r) {
  std::vector<LabelledAnalysis> curves;
  for (const auto& v : r.shaft_damping_variants)
    curves.push_back({fmt("b3 = %g N m s/rad", v.params.shaft_damping) +
                          (v.resonance ? fmt(" (peak %+.1f dB)", v.resonance->peak_height_db) : std::string()),
                      &v});
  return bode_figure("Effect of the shaft damping b3 (scene " + r.scene_name + ")", curves);
}

plot::Figure load_inertia_bode(const MotorBodeResult& r) {
  return bode_figure(fmt("Effect of a load inertia %.3g kg m^2 added to the rotor (I1 = %.3g kg m^2)", r.load_inertia,
                         r.with_load.params.motor_inertia),
                     {{"motor and tacho alone", &r.nominal},
                      {fmt("with load inertia %.3g kg m^2", r.load_inertia), &r.with_load}});
}

plot::Figure position_figure(const SlideModesResult& r) {
  plot::Series ritz{.label = fmt("Rayleigh-Ritz, %g cosines", static_cast<double>(r.settings.ritz_shapes))};
  plot::Series converged{.label = fmt("FE chain, %g elements (converged)", static_cast<double>(r.settings.sweep_fe_elements)),
                         .style = "dashed"};
  for (const auto& p : r.f0_vs_position) {
    ritz.x.push_back(p.position * 1e3), ritz.y.push_back(p.ritz_hz);
    converged.x.push_back(p.position * 1e3), converged.y.push_back(p.converged_hz);
  }
  plot::Panel panel{.title = "Model 3 (continuous shaft, free-free): lowest non-rigid mode",
                    .xlabel = "slide position x from the drive end [mm]",
                    .ylabel = "f0 [Hz]",
                    .series = {ritz, converged}};
  panel.series.push_back({.label = fmt("analysed position, %.1f Hz", r.model3_hz),
                          .x = {r.slide_position * 1e3},
                          .y = {r.model3_hz},
                          .style = "points"});
  if (r.first_mode_node)
    panel.series.push_back({.label = fmt("node of the first mode, x = %.0f mm", r.first_mode_node->position * 1e3),
                            .x = {r.first_mode_node->position * 1e3},
                            .y = {r.first_mode_node->frequency_hz},
                            .style = "points"});
  return {.title = "f0 against the slide position (scene " + r.scene_name + ")", .panels = {panel}};
}

plot::Figure diameter_figure(const SlideModesResult& r) {
  plot::Series m1{.label = "model 1: two inertias"};
  plot::Series m2a{.label = "model 2: grounded chain, 1st", .style = "dashed"};
  plot::Series m2b{.label = "model 2: grounded chain, 2nd", .style = "dashed"};
  plot::Series m3{.label = fmt("model 3: continuous shaft, %g cosines", static_cast<double>(r.settings.ritz_shapes)), .style = "linespoints"};
  plot::Series m3c{.label = fmt("model 3: FE chain, %g elements", static_cast<double>(r.settings.sweep_fe_elements))};
  for (const auto& p : r.f0_vs_diameter) {
    const double d = p.diameter * 1e3;
    m1.x.push_back(d), m1.y.push_back(p.model1_hz);
    m2a.x.push_back(d), m2a.y.push_back(p.model2.first_hz);
    m2b.x.push_back(d), m2b.y.push_back(p.model2.second_hz);
    m3.x.push_back(d), m3.y.push_back(p.model3_hz);
    m3c.x.push_back(d), m3c.y.push_back(p.model3_converged_hz);
  }
  plot::Panel panel{.title = fmt("Eigenfrequencies against the spindle diameter (model 3 at x = %.0f mm)",
                                 r.slide_position * 1e3),
                    .xlabel = "spindle diameter [mm]",
                    .ylabel = "f [Hz]",
                    .series = {m1, m2a, m2b, m3, m3c}};
  return {.title = "f0 against the spindle diameter (scene " + r.scene_name + ")", .panels = {panel}};
}

plot::Figure convergence_figure(const SlideModesResult& r) {
  plot::Series ritz{.label = "Rayleigh-Ritz (N cosines)", .style = "linespoints"};
  plot::Series fe{.label = "FE chain (N elements)", .style = "linespoints"};
  for (const auto& p : r.ritz_convergence) ritz.x.push_back(p.count), ritz.y.push_back(p.frequency_hz);
  for (const auto& p : r.fe_convergence) fe.x.push_back(p.count), fe.y.push_back(p.frequency_hz);
  plot::Panel values{.title = fmt("Model 3 at x = %.0f mm", r.slide_position * 1e3),
                     .xlabel = "N",
                     .ylabel = "f0 [Hz]",
                     .series = {ritz, fe},
                     .logx = true};
  std::vector<plot::Panel> panels{values};
  if (r.model3_extrapolated_hz) {
    // Errors against the Richardson value of the two finest meshes: Ritz falls as about
    // 1/N from above, the lumped-mass chain as 1/N² from below.
    const double reference = *r.model3_extrapolated_hz;
    plot::Series ritz_error{.label = "Rayleigh-Ritz", .style = "linespoints"};
    plot::Series fe_error{.label = "FE chain", .style = "linespoints"};
    for (const auto& p : r.ritz_convergence)
      ritz_error.x.push_back(p.count), ritz_error.y.push_back(std::abs(p.frequency_hz - reference) / reference);
    // The finest mesh defines the reference with its neighbour: leave it out.
    for (std::size_t i = 0; i + 1 < r.fe_convergence.size(); ++i)
      fe_error.x.push_back(r.fe_convergence[i].count),
          fe_error.y.push_back(std::abs(r.fe_convergence[i].frequency_hz - reference) / reference);
    panels.push_back({.title = fmt("Relative error against the extrapolated %.3f Hz", reference),
                      .xlabel = "N",
                      .ylabel = "|f0 - f_ref| / f_ref",
                      .series = {ritz_error, fe_error},
                      .logx = true,
                      .logy = true});
  }
  return {.title = "Convergence of model 3 (scene " + r.scene_name + ")", .panels = panels};
}

}  // namespace

std::vector<NamedFigure> motor_bode_figures(const MotorBodeResult& r) {
  std::vector<NamedFigure> figures{{"bode.png", with_room_for_keys(nominal_bode(r))}};
  if (!r.shaft_damping_variants.empty())
    figures.push_back({"bode_b3_variants.png", with_room_for_keys(b3_variants_bode(r))});
  figures.push_back({"bode_load_inertia.png", with_room_for_keys(load_inertia_bode(r))});
  return figures;
}

std::vector<NamedFigure> slide_modes_figures(const SlideModesResult& r) {
  return {{"f0_vs_position.png", with_room_for_keys(position_figure(r))},
          {"f0_vs_diameter.png", with_room_for_keys(diameter_figure(r))},
          {"model3_convergence.png", with_room_for_keys(convergence_figure(r))}};
}

}  // namespace mechsim::tools::nc_analyses
