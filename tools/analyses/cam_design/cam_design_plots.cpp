#include "cam_design_plots.h"

#include <cmath>
#include <algorithm>

#include "mechsim/models/constants.h"
#include "text_format.h"

namespace mechsim::tools::cam_design {

namespace cam = models::cam;
using plot::Figure;
using plot::Panel;
using plot::Series;

namespace {

using models::pi;
using models::degree;
using models::nan;
const std::string theta_label = "cam angle theta [deg]";

// A series over the cycle from samples: x in deg, y = value(sample).
template <class Sample, class F>
Series over_cycle(const std::vector<Sample>& samples, std::string label, F value, std::string style = "lines") {
  Series s{std::move(label), {}, {}, std::move(style)};
  for (const auto& p : samples) {
    s.x.push_back(p.theta_rad / degree);
    s.y.push_back(value(p));
  }
  // Close the cycle at 360° with the value at 0° (the law is periodic).
  if (!samples.empty()) {
    s.x.push_back(360.0);
    s.y.push_back(value(samples.front()));
  }
  return s;
}

Series circle(std::string label, double radius_mm, std::string style) {
  Series s{std::move(label), {}, {}, std::move(style)};
  for (int i = 0; i <= 360; ++i) {
    s.x.push_back(radius_mm * std::sin(i * degree));
    s.y.push_back(radius_mm * std::cos(i * degree));
  }
  return s;
}

Series single_point(std::string label, double x, double y) { return {std::move(label), {x}, {y}, "points"}; }

// A vertical dashed line at x from y0 to y1: marks an angle more visibly than a point.
Series marker(std::string label, double x, double y0, double y1) {
  return {std::move(label), {x, x}, {y0, y1}, "dashed"};
}

std::vector<NamedFigure> roller_figures(const std::string& scene, const RollerDesign& d) {
  const auto& c = d.cycle;
  const auto& k = d.contour;
  const cam::CamDesignReport& r = d.report;
  const cam::CamDesignInput& in = d.input_case.input;
  const double r0_mm = in.geometry.pitch_radius_m * 1e3;
  const double rr_mm = in.geometry.roller_radius_m * 1e3;
  std::vector<NamedFigure> out;

  {
    Figure f{"Motion law of '" + scene + "' (" + r.continuity.summary() + ")", {}, 1000, 260};
    f.panels.push_back(Panel{"lift S", theta_label, "S [mm]", {over_cycle(c, "S", [](auto& p) { return p.lift_m * 1e3; })}});
    f.panels.push_back(Panel{"velocity S' = dS/dtheta", theta_label, "S' [mm/rad]",
                             {over_cycle(c, "S'", [](auto& p) { return p.lift_d1 * 1e3; })}});
    f.panels.push_back(Panel{"acceleration S'' = d2S/dtheta2", theta_label, "S'' [mm/rad^2]",
                             {over_cycle(c, "S''", [](auto& p) { return p.lift_d2 * 1e3; })}});
    out.push_back({"motion_law.png", f});
  }
  {
    const double limit = in.pressure_angle_limit_rad / degree;
    Panel alpha{"pressure angle (e = " + fmt("%.4g", in.geometry.eccentricity_m * 1e3) + " mm): max " +
                    fmt("%.2f", r.pressure_angle.max.value / degree) + " deg, min " +
                    fmt("%.2f", r.pressure_angle.min.value / degree) + " deg",
                theta_label, "alpha [deg]",
                {over_cycle(c, "alpha", [](auto& p) { return p.pressure_angle_rad / degree; })}};
    alpha.hlines = {{limit, "+limit"}, {-limit, "-limit"}};
    // Room above the limit lines, which autoscaling would put on the frame.
    const double span = 1.15 * std::max({limit, std::abs(r.pressure_angle.max.value / degree),
                                         std::abs(r.pressure_angle.min.value / degree)});
    alpha.yrange = std::make_pair(-span, span);
    // rho passes through infinity at an inflexion of the pitch curve: clip the view and
    // break the line where it leaves it, so the spikes do not draw vertical strokes.
    const double clip = 3.0 * r0_mm;
    auto clipped = [clip](double v_mm) { return std::abs(v_mm) > 3.0 * clip ? nan : v_mm; };
    Panel rho{"radius of curvature (> 0 convex): pitch curve min " + fmt("%.2f", r.curvature.min_positive_rho_m * 1e3) +
                  " mm, " + (r.curvature.undercut ? "UNDERCUT" : "no undercut"),
              theta_label, "rho [mm]",
              {over_cycle(k, "pitch curve rho_p", [&](auto& p) { return clipped(p.pitch_rho_m * 1e3); }),
               over_cycle(k, "cam contour rho_c = rho_p - Rr", [&](auto& p) { return clipped(p.contour_rho_m * 1e3); },
                          "dashed")}};
    rho.yrange = std::make_pair(-clip, clip);
    rho.hlines = {{rr_mm, "roller radius Rr (undercut below, convex side)"}, {0.0, ""}};
    out.push_back({"pressure_angle_curvature.png", Figure{"Pressure angle and curvature of '" + scene + "'", {alpha, rho}}});
  }
  {
    Panel parts{"force components (+ = the cam must supply it)", theta_label, "force [N]",
                {over_cycle(c, "functional load", [](auto& p) { return p.functional_load_n; }),
                 over_cycle(c, "spring", [](auto& p) { return p.spring_force_n; }),
                 over_cycle(c, "inertia m w^2 S''", [](auto& p) { return p.inertia_force_n; }),
                 over_cycle(c, "N cos alpha (sum)", [](auto& p) { return p.contact_force_n * std::cos(p.pressure_angle_rad); },
                            "dashed")}};
    Panel contact{"contact force N: min " + fmt("%.1f", r.contact_force.min.contact_force_n) + " N with spring, " +
                      fmt("%.1f", r.contact_force_without_spring.min.contact_force_n) + " N without",
                  theta_label, "N [N]",
                  {over_cycle(c, "with spring", [](auto& p) { return p.contact_force_n; }),
                   over_cycle(c, "without spring", [](auto& p) { return p.contact_force_without_spring_n; }, "dashed")}};
    contact.hlines = {{0.0, "lift-off below"}};
    out.push_back({"forces.png", Figure{"Forces on the follower of '" + scene + "' at " +
                                            fmt("%.4g", in.speed_rad_s * 30.0 / pi) + " rpm",
                                        {parts, contact}}});
  }
  {
    const auto& t = r.torque;
    Panel torque{"drive torque M = N cos(alpha) S': mean " + fmt("%.4g", t.mean_torque_nm) + " N m (" +
                     fmt("%.3g", t.mean_power_w) + " W)",
                 theta_label, "M [N m]", {over_cycle(c, "M", [](auto& p) { return p.drive_torque_nm; })}};
    torque.hlines = {{t.mean_torque_nm, "mean"}};
    Panel area{"flywheel: A(theta) = integral of (M - M_mean), A_max = " + fmt("%.4g", t.a_max_j) + " J -> I = " +
                   fmt("%.4g", r.flywheel.inertia_kgm2) + " kg m^2",
               theta_label, "A [J]",
               {over_cycle(c, "A(theta)", [](auto& p) { return p.a_j; }),
                marker("theta_m = " + fmt("%.2f", t.theta_a_min_rad / degree) + " deg (min A, fastest)",
                       t.theta_a_min_rad / degree, t.a_min_j, t.a_max_value_j),
                marker("theta_M = " + fmt("%.2f", t.theta_a_max_rad / degree) + " deg (max A, slowest)",
                       t.theta_a_max_rad / degree, t.a_min_j, t.a_max_value_j)}};
    area.hlines = {{t.a_min_j, ""}, {t.a_max_value_j, ""}};
    out.push_back({"drive_torque_flywheel.png", Figure{"Drive torque and flywheel of '" + scene + "'", {torque, area}}});
  }
  {
    const auto& sr = r.single_rise;
    Series excitation{"theta(tau) (cam)", {}, {}, "dashed"}, response{"gamma(tau) (follower)", {}, {}, "lines"};
    Series error{"gamma - theta", {}, {}, "lines"};
    for (const auto& s : sr.samples) {
      excitation.x.push_back(s.tau), excitation.y.push_back(s.excitation);
      response.x.push_back(s.tau), response.y.push_back(s.gamma);
      error.x.push_back(s.tau), error.y.push_back(s.gamma - s.excitation);
    }
    Panel single{"single rise (critical event, lambda = " + fmt("%.4g", sr.lambda) + ")", "tau = t / t_event", "normalised lift",
                 {excitation, response}};
    Panel single_error{"single rise error: max " + fmt("%.3e", sr.max_error) + " in the event, residual " +
                           fmt("%.2e", sr.residual_amplitude),
                       "tau = t / t_event", "gamma - theta", {error}};
    Series multi{"gamma - theta", {}, {}, "lines"};
    for (const auto& s : r.multi_rise.samples) {
      multi.x.push_back(s.tau * 360.0);
      multi.y.push_back(s.gamma - s.excitation);
    }
    Panel multi_error{"multi rise error (lambda' = " + fmt("%.4g", r.lambda_prime) + ", cycle " +
                          std::to_string(r.multi_rise.cycles) + "): max " + fmt("%.3e", r.multi_rise.max_error),
                      theta_label, "gamma - theta", {multi}};
    out.push_back({"follower_error.png",
                   Figure{"Flexible follower error of '" + scene + "'", {single, single_error, multi_error}, 1000, 260}});
  }
  {
    Series pitch{"pitch curve (roller centre)", {}, {}, "dashed"}, contour{"cam contour", {}, {}, "lines"};
    for (const auto& p : k) {
      pitch.x.push_back(p.pitch.x * 1e3), pitch.y.push_back(p.pitch.y * 1e3);
      contour.x.push_back(p.contour.x * 1e3), contour.y.push_back(p.contour.y * 1e3);
    }
    if (!k.empty()) {  // close the curves
      pitch.x.push_back(pitch.x.front()), pitch.y.push_back(pitch.y.front());
      contour.x.push_back(contour.x.front()), contour.y.push_back(contour.y.front());
    }
    Panel panel{"cam-fixed frame, theta = 0 along +y, follower axis x = e", "x [mm]", "y [mm]",
                {contour, pitch, circle("base circle R0 - Rr = " + fmt("%.4g", r0_mm - rr_mm) + " mm", r0_mm - rr_mm, "dashed"),
                 single_point("shaft centre", 0.0, 0.0)}};
    panel.equal_axes = true;
    out.push_back({"cam_contour.png", Figure{"Cam contour of '" + scene + "' (to scale)", {panel}, 800, 800}});
  }
  return out;
}

std::vector<NamedFigure> flat_face_figures(const std::string& scene, const FlatFaceDesign& d) {
  const auto& pts = d.points;
  const auto& a = d.analysis;
  std::vector<NamedFigure> out;
  {
    Figure f{"Flat-faced follower of '" + scene + "': cycloidal rise and return", {}, 1000, 260};
    f.panels.push_back(Panel{"lift s", theta_label, "s [mm]", {over_cycle(pts, "s", [](auto& p) { return p.lift_m * 1e3; })}});
    f.panels.push_back(Panel{"contact offset q = ds/dtheta (face half-width >= " + fmt("%.3g", a.max_offset_m * 1e3) + " mm)",
                             theta_label, "q [mm]", {over_cycle(pts, "q", [](auto& p) { return p.offset_m * 1e3; })}});
    f.panels.push_back(Panel{"acceleration", theta_label, "s'' w^2 [m/s^2]",
                             {over_cycle(pts, "acceleration", [](auto& p) { return p.acceleration; })}});
    out.push_back({"motion_law.png", f});
  }
  {
    Series contour{"cam contour", {}, {}, "lines"};
    for (const auto& p : pts) contour.x.push_back(p.contour.x * 1e3), contour.y.push_back(p.contour.y * 1e3);
    if (!pts.empty()) contour.x.push_back(contour.x.front()), contour.y.push_back(contour.y.front());
    const double rb_mm = d.params.base_radius_m * 1e3;
    Panel panel{"cam-fixed frame, theta = 0 along +y; min radius of curvature " + fmt("%.3g", a.min_curvature_radius_m * 1e3) + " mm",
                "x [mm]", "y [mm]",
                {contour, circle("base circle R_b = " + fmt("%.4g", rb_mm) + " mm", rb_mm, "dashed"),
                 single_point("shaft centre", 0.0, 0.0)}};
    panel.equal_axes = true;
    out.push_back({"cam_contour.png", Figure{"Cam contour of '" + scene + "' (to scale)", {panel}, 800, 800}});
  }
  {
    Panel force{"contact force F_c = k (s + x0) + m s'' w^2: min " + fmt("%.4g", a.min_contact_force_n) + " N", theta_label,
                "F_c [N]", {over_cycle(pts, "F_c", [](auto& p) { return p.contact_force_n; })}};
    force.hlines = {{0.0, "lift-off below"}};
    Panel torque{"drive torque M = F_c q: energy fluctuation dE = " + fmt("%.4g", a.delta_e_j) + " J", theta_label, "M [N m]",
                 {over_cycle(pts, "M", [](auto& p) { return p.torque_nm; })}};
    torque.hlines = {{a.mean_torque_nm, "mean"}};
    Panel power{"power P = M w: peak " + fmt("%.4g", a.peak_power_w) + " W", theta_label, "P [W]",
                {over_cycle(pts, "P", [](auto& p) { return p.power_w; })}};
    out.push_back({"torque_power.png", Figure{"Force, torque and power of '" + scene + "'", {force, torque, power}, 1000, 260}});
  }
  return out;
}

// gnuplot 5.4 misreads two escaped quotes in a row (the label S'' becomes 'S''''' in the
// script): write a double prime as " in every text of a figure.
void write_double_primes_as_quotes(std::string& text) {
  for (std::size_t at = text.find("''"); at != std::string::npos; at = text.find("''", at + 1))
    text.replace(at, 2, "\"");
}

void write_double_primes_as_quotes(Figure& f) {
  write_double_primes_as_quotes(f.title);
  for (auto& panel : f.panels) {
    for (auto* text : {&panel.title, &panel.xlabel, &panel.ylabel}) write_double_primes_as_quotes(*text);
    for (auto& series : panel.series) write_double_primes_as_quotes(series.label);
    for (auto& line : panel.hlines) write_double_primes_as_quotes(line.second);
  }
}

}  // namespace

std::vector<NamedFigure> design_figures(const CamDesignResult& result) {
  std::vector<NamedFigure> out;
  if (result.roller) out = roller_figures(result.scene_name, *result.roller);
  if (result.flat_face) out = flat_face_figures(result.scene_name, *result.flat_face);
  for (auto& f : out) write_double_primes_as_quotes(f.figure);
  return out;
}

PlotOutcome write_plots(const std::string& dir, const CamDesignResult& result) {
  return plot::write_figures(dir, design_figures(result));
}

}  // namespace mechsim::tools::cam_design
