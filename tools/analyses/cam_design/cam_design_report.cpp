#include "cam_design_report.h"

#include <cmath>
#include <stdexcept>

#include "mechsim/models/constants.h"
#include "text_format.h"

namespace mechsim::tools::cam_design {

namespace cam = models::cam;

namespace {

using models::pi;
using models::degree;
using models::rpm;

double wrap_deg(double rad) {
  const double d = std::fmod(rad / degree, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

RollerDesign analyse_roller(const config::Scene& scene, const DesignSettings& settings) {
  RollerDesign d;
  d.input_case = roller_case_from_scene(scene, settings);
  const cam::CamDesignInput& in = d.input_case.input;
  d.report = cam::analyse_cam_design(in);
  const cam::MotionLaw law(in.segments);
  d.contour = cam::sample_contour(law, in.geometry, contour_samples);
  d.cycle = cam::sample_cycle(law, in.geometry, in.follower, in.speed_rad_s, cycle_samples);
  return d;
}

FlatFaceDesign analyse_flat_face(const DesignSettings& settings) {
  FlatFaceDesign d{};
  d.params = *settings.flat_face;
  d.analysis = cam::analyse_flat_face(d.params);
  d.flywheel_inertia_kgm2 =
      cam::flat_face_flywheel_inertia(d.analysis, d.params.speed_rad_s, settings.speed_fluctuation);
  d.flywheel_disc_radius_m = std::pow(
      2.0 * d.flywheel_inertia_kgm2 / (pi * settings.flywheel_thickness_m * settings.flywheel_density_kg_m3), 0.25);
  // F_c is the roller follower's N cos α with no functional load (spec §3 and §6 share
  // F0 + k s + m ω² s''), so the kinetostatic lift-off speed is the same computation.
  const models::follower::FollowerParams follower{
      d.params.mass_kg, {d.params.spring_stiffness_n_per_m, d.params.spring_preload_n}, {}};
  d.lift_off = cam::kinetostatic_lift_off_speed(cam::flat_face_law(d.params), follower);
  for (int i = 0; i < contour_samples; ++i)
    d.points.push_back(cam::flat_face_point(d.params, 2.0 * pi * i / contour_samples));
  return d;
}

}  // namespace

CamDesignResult analyse_scene(const config::Scene& scene, std::vector<std::string> overrides) {
  CamDesignResult r;
  r.scene_name = scene.name;
  r.scene_file = scene.file;
  r.overrides = std::move(overrides);
  r.settings = parse_design_settings(scene.design);
  if (r.settings.follower == FollowerKind::flat_face)
    r.flat_face = analyse_flat_face(r.settings);
  else
    r.roller = analyse_roller(scene, r.settings);
  return r;
}

std::string lift_off_line(const cam::LiftOffSpeed& l) {
  if (std::isinf(l.speed_rad_s)) return "lift-off speed (rigid follower): none, the follower never lifts off";
  if (l.speed_rad_s == 0.0)
    return fmt("lift-off speed (rigid follower): 0 rpm, the static forces open the contact at %.2f deg",
                  wrap_deg(l.angle_rad));
  return fmt("lift-off speed (rigid follower): %.2f rpm (%.4g rad/s), first at %.2f deg (lift %.3f mm)",
                l.speed_rad_s / rpm, l.speed_rad_s, wrap_deg(l.angle_rad), l.lift_m * 1e3);
}

std::vector<std::string> summary_lines(const CamDesignResult& result) {
  std::vector<std::string> out;
  if (result.flat_face) {
    const FlatFaceDesign& f = *result.flat_face;
    const auto& a = f.analysis;
    out.push_back(fmt("cam design of '%s': flat-faced follower, h = %.4g mm, beta = %.4g deg, R_b = %.4g mm, %.4g rpm",
                         result.scene_name.c_str(), f.params.lift_m * 1e3, f.params.span_rad / degree,
                         f.params.base_radius_m * 1e3, f.params.speed_rad_s / rpm));
    out.push_back(fmt("  energy fluctuation dE      %.6g J (closed form k(h^2/2 + x0 h) = %.6g J)", a.delta_e_j,
                         a.delta_e_closed_form_j));
    out.push_back(fmt("  peak power                 %.6g W at %.2f deg", a.peak_power_w, wrap_deg(a.angle_peak_power_rad)));
    out.push_back(fmt("  mean torque                %.3g N m", a.mean_torque_nm));
    out.push_back(fmt("  contact force min          %.6g N at %.2f deg (%s)", a.min_contact_force_n,
                         wrap_deg(a.angle_min_contact_force_rad), a.contact_everywhere ? "contact everywhere" : "LIFTS OFF"));
    out.push_back(fmt("  contour curvature min      %.4g mm (must stay > 0)", a.min_curvature_radius_m * 1e3));
    out.push_back(fmt("  follower face half-width   >= %.4g mm (max |q|)", a.max_offset_m * 1e3));
    out.push_back(fmt("  flywheel                   I = %.6g kg m^2, disc radius %.4g mm (K = %.3g)",
                         f.flywheel_inertia_kgm2, f.flywheel_disc_radius_m * 1e3, result.settings.speed_fluctuation));
    out.push_back("  " + lift_off_line(f.lift_off));
    return out;
  }
  const RollerDesign& d = *result.roller;
  const cam::CamDesignReport& r = d.report;
  const cam::CamDesignInput& in = d.input_case.input;
  out.push_back(fmt("cam design of '%s': roller follower ('%s' on '%s'), R0 = %.4g mm, Rr = %.4g mm, e = %.4g mm, %.4g rpm",
                       result.scene_name.c_str(), d.input_case.follower_participant.c_str(),
                       d.input_case.cam_participant.c_str(), in.geometry.pitch_radius_m * 1e3,
                       in.geometry.roller_radius_m * 1e3, in.geometry.eccentricity_m * 1e3, in.speed_rad_s / rpm));
  for (const auto& note : d.input_case.notes) out.push_back("  note: " + note);
  out.push_back("  continuity                 " + r.continuity.summary());
  if (const auto& m = d.input_case.c1_match)
    out.push_back(fmt("  beta1 (C1 matched to C2)   %.6g deg (scene: %.6g deg, %s)", m->matched_span_rad / degree,
                         m->scene_span_rad / degree, m->scene_span_matches ? "equal" : "DIFFERENT"));
  out.push_back(fmt("  pressure angle max         %.4f deg at %.2f deg", r.pressure_angle.max.value / degree,
                       wrap_deg(r.pressure_angle.max.angle_rad)));
  out.push_back(fmt("  pressure angle min         %.4f deg at %.2f deg (limit +-%.4g deg: %s)",
                       r.pressure_angle.min.value / degree, wrap_deg(r.pressure_angle.min.angle_rad),
                       in.pressure_angle_limit_rad / degree, r.pressure_angle_within_limit ? "ok" : "EXCEEDED"));
  for (const auto& p : r.curvature.pieces) {
    if (p.filler || p.segment.type == cam::SegmentType::dwell) continue;
    out.push_back(fmt("  rho_pitch min %-18s %.4f mm at %.2f deg", cam::segment_type_name(p.segment.type),
                         p.min_positive_rho_m * 1e3, wrap_deg(p.angle_min_positive_rad)));
  }
  out.push_back(fmt("  undercut                   %s (min contour rho %.4g mm)", r.curvature.undercut ? "YES" : "no",
                       r.curvature.min_contour_rho_m * 1e3));
  out.push_back(fmt("  optimal eccentricity       %.4f mm (alpha %.4f / %.4f deg)",
                       r.optimal_eccentricity.eccentricity_m * 1e3, r.optimal_eccentricity.alpha.max.value / degree,
                       r.optimal_eccentricity.alpha.min.value / degree));
  out.push_back(fmt("  contact force min          %.4f N at %.2f deg (max %.4f N at %.2f deg)",
                       r.contact_force.min.contact_force_n, wrap_deg(r.contact_force.min.angle_rad),
                       r.contact_force.max.contact_force_n, wrap_deg(r.contact_force.max.angle_rad)));
  out.push_back(fmt("  contact force min, no spring %.4f N at %.2f deg (lift %.3f mm)",
                       r.contact_force_without_spring.min.contact_force_n,
                       wrap_deg(r.contact_force_without_spring.min.angle_rad),
                       r.contact_force_without_spring.min.lift_m * 1e3));
  out.push_back(fmt("  minimum spring rate        %.4f N/mm for preload %.4g N%s", r.minimum_spring.min_stiffness_n_per_m / 1e3,
                       in.follower.spring.preload_n, r.minimum_spring.feasible ? "" : " (NOT FEASIBLE: preload too small)"));
  out.push_back(fmt("  mean power                 %.4f W", r.torque.mean_power_w));
  out.push_back(fmt("  theta at A min / A max     %.2f / %.2f deg, A_max = %.5g J", wrap_deg(r.torque.theta_a_min_rad),
                       wrap_deg(r.torque.theta_a_max_rad), r.torque.a_max_j));
  out.push_back(fmt("  flywheel                   I = %.5g kg m^2, disc radius %.4g mm (K = %.3g)",
                       r.flywheel.inertia_kgm2, r.flywheel.disc_radius_m * 1e3, in.speed_fluctuation));
  out.push_back(fmt("  speed extremes             max %.4g rpm at %.2f deg, min %.4g rpm at %.2f deg",
                       r.flywheel.speed_max_rad_s / rpm, wrap_deg(r.flywheel.theta_speed_max_rad),
                       r.flywheel.speed_min_rad_s / rpm, wrap_deg(r.flywheel.theta_speed_min_rad)));
  out.push_back(fmt("  follower stiffness k_f     %.2f N/mm (lambda %.4g over the %.4g deg event)",
                       r.follower_stiffness_n_per_m / 1e3, in.lambda, r.events[r.critical_event].span_rad / degree));
  out.push_back(fmt("  lambda multi               %.4f", r.lambda_prime));
  out.push_back(fmt("  single rise max error      %.4e (residual %.3e, approx %.3e)", r.single_rise.max_error,
                       r.single_rise.residual_amplitude, r.single_rise.approx_residual_amplitude));
  out.push_back(fmt("  multi rise max error       %.4e at %.2f deg (cycle %d)", r.multi_rise.max_error,
                       wrap_deg(r.multi_rise.theta_max_error_rad), r.multi_rise.cycles));
  out.push_back("  " + lift_off_line(r.lift_off));
  return out;
}

}  // namespace mechsim::tools::cam_design
