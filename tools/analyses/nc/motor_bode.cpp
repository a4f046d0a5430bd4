#include "motor_bode.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mechsim/models/constants.h"
#include "text_format.h"

namespace mechsim::tools::nc_analyses {

namespace nc = models::nc;

namespace {

using models::two_pi;

BodeCurve bode_curve(const nc::MotorTachoParams& params, const MotorBodeSettings& s) {
  const double decades = std::log10(s.frequency_to_hz / s.frequency_from_hz);
  const int points = static_cast<int>(std::ceil(decades * s.points_per_decade)) + 1;
  BodeCurve curve;
  for (int i = 0; i < points; ++i) {
    const double f = s.frequency_from_hz * std::pow(10.0, decades * i / (points - 1));
    const nc::FrequencyPoint p = nc::frequency_response(params, f);
    curve.frequency_hz.push_back(f);
    curve.magnitude_db.push_back(p.magnitude_db);
    curve.phase_deg.push_back(p.phase_deg);
  }
  return curve;
}

}  // namespace

MotorTachoAnalysis analyse_motor_tacho(const nc::MotorTachoParams& params, const MotorBodeSettings& settings) {
  MotorTachoAnalysis a;
  a.params = params;
  a.transfer_function = nc::tacho_transfer_function(params);
  a.poles = nc::poles(params);
  a.dc_gain = nc::dc_gain(params);
  a.corner_hz = nc::corner_frequency_hz(params);
  try {
    a.resonance = nc::resonance(params);
  } catch (const std::domain_error&) {
    // Overdamped shaft mode (large b3): no resonance to report.
  }
  a.approximations = nc::pole_approximations(params);
  std::vector<double> real_hz;
  for (const auto& p : a.poles) {
    if (p.imag() == 0.0)
      real_hz.push_back(std::abs(p) / two_pi);
    else
      a.exact_shaft_pair_hz = std::abs(p) / two_pi;
  }
  std::sort(real_hz.begin(), real_hz.end());
  if (real_hz.size() >= 2) a.exact_slow_pole_hz = real_hz.front();
  if (real_hz.size() == 2) a.exact_electrical_pole_hz = real_hz.back();
  double min_abs = INFINITY, max_abs = 0, min_re = INFINITY, max_re = 0;
  for (const auto& p : a.poles) {
    min_abs = std::min(min_abs, std::abs(p)), max_abs = std::max(max_abs, std::abs(p));
    min_re = std::min(min_re, std::abs(p.real())), max_re = std::max(max_re, std::abs(p.real()));
  }
  a.stiffness_ratio = max_abs / min_abs;
  a.real_part_ratio = max_re / min_re;
  a.bode = bode_curve(params, settings);
  return a;
}

MotorBodeResult analyse_motor_bode(const config::Scene& scene, std::vector<std::string> overrides) {
  MotorBodeResult r;
  r.scene_name = scene.name;
  r.scene_file = scene.file;
  r.overrides = std::move(overrides);
  const NcDesignSettings settings = parse_nc_design_settings(scene.design);
  r.settings = settings.motor_bode;
  r.motor = motor_case_from_scene(scene, settings);
  r.nominal = analyse_motor_tacho(r.motor.params, r.settings);
  for (double b3 : r.settings.shaft_damping_variants) {
    nc::MotorTachoParams variant = r.motor.params;
    variant.shaft_damping = b3;
    r.shaft_damping_variants.push_back(analyse_motor_tacho(variant, r.settings));
  }
  // Parsed even with the load inertia given, so that bad slide data is refused by either command.
  const SlideCase slide = slide_case_from_scene(scene, settings);
  if (r.settings.load_inertia) {
    r.load_inertia = *r.settings.load_inertia;
    r.load_inertia_source = "design.motor_bode.load_inertia";
  } else {
    // The drive train behind the coupling as one rigid body: what the motor sees at low
    // frequency (spec §2, "rigid").
    r.load_inertia = slide.data.coupling_inertia + slide.data.spindle_inertia() + slide.data.slide_inertia();
    r.load_inertia_source = "I_kopp + I_sp + I_slide of the slide data (" +
                            (slide.source.where.empty() ? slide.source.kind : slide.source.where) + ")";
  }
  r.with_load = analyse_motor_tacho(nc::with_load_inertia(r.motor.params, r.load_inertia), r.settings);
  return r;
}

std::vector<std::string> motor_bode_summary(const MotorBodeResult& r) {
  const MotorTachoAnalysis& n = r.nominal;
  std::vector<std::string> lines;
  lines.push_back("motor-bode: scene '" + r.scene_name + "', motor data from " +
                  (r.motor.source.where.empty() ? r.motor.source.kind : r.motor.source.where));
  for (const auto& note : r.motor.notes) lines.push_back("  note: " + note);
  lines.push_back(fmt("  DC gain U_T/U_a        %.4f V/V", n.dc_gain));
  lines.push_back(fmt("  -3 dB corner           %.2f Hz", n.corner_hz));
  if (n.resonance)
    lines.push_back(fmt("  shaft resonance        %.1f Hz, peak %+.2f dB over DC (natural %.1f Hz, damping %.4f)",
                        n.resonance->frequency_hz, n.resonance->peak_height_db, n.resonance->natural_frequency_hz,
                        n.resonance->damping_ratio));
  else
    lines.push_back("  shaft resonance        none (shaft mode overdamped)");
  for (const auto& p : n.poles)
    lines.push_back(fmt("  pole                   %12.2f %+12.2fj 1/s  (%.2f Hz)", p.real(), p.imag(),
                        std::abs(p) / two_pi));
  lines.push_back(fmt("  approximations (3)-(5) s1 %.2f Hz, s2 %.1f Hz, f0 %.1f Hz", n.approximations.slow_pole_hz,
                      n.approximations.electrical_pole_hz, n.approximations.resonance_hz));
  for (const auto& v : r.shaft_damping_variants)
    lines.push_back(v.resonance ? fmt("  b3 = %-8g N m s/rad   resonance %.1f Hz, peak %+.2f dB", v.params.shaft_damping,
                                      v.resonance->frequency_hz, v.resonance->peak_height_db)
                                : fmt("  b3 = %-8g N m s/rad   no resonance (overdamped)", v.params.shaft_damping));
  lines.push_back(fmt("  load inertia %.4g kg m^2: corner %.2f Hz", r.load_inertia, r.with_load.corner_hz) +
                  (r.with_load.resonance ? fmt(", resonance %.1f Hz, peak %+.2f dB", r.with_load.resonance->frequency_hz,
                                               r.with_load.resonance->peak_height_db)
                                         : std::string(", no resonance")));
  return lines;
}

}  // namespace mechsim::tools::nc_analyses
