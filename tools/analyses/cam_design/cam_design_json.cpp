#include "cam_design_json.h"

#include <cmath>

#include "json_io.h"
#include "mechsim/models/constants.h"
#include "provenance.h"

namespace mechsim::tools::cam_design {

namespace cam = models::cam;
using nlohmann::json;

namespace {

using models::pi;
using models::degree;
using models::rpm;

json mm(double m) { return finite_or_null(m * 1e3); }
json law_index(const std::optional<std::size_t>& i) { return i ? json(*i) : json(nullptr); }

json settings_json(const DesignSettings& s) {
  return {{"follower", s.follower == FollowerKind::flat_face ? "flat_face" : "roller"},
          {"speed_fluctuation", s.speed_fluctuation},
          {"flywheel_density_kg_per_m3", s.flywheel_density_kg_m3},
          {"flywheel_thickness_mm", s.flywheel_thickness_m * 1e3},
          {"lambda", s.lambda},
          {"damping_ratio", s.damping_ratio},
          {"multi_rise_cycles", s.multi_rise_cycles},
          {"pressure_angle_limit_deg", s.pressure_angle_limit_rad / degree},
          {"match_c1_to_c2", s.match_c1_to_c2}};
}

void add_roller(json& j, const RollerDesign& d) {
  const cam::CamDesignInput& in = d.input_case.input;
  const cam::CamDesignReport& r = d.report;
  const cam::MotionLaw law(in.segments);

  j["participants"] = {{"cam_shaft", d.input_case.cam_participant}, {"follower", d.input_case.follower_participant}};
  j["notes"] = d.input_case.notes;
  json loads = json::array();
  for (const auto& l : in.follower.loads)
    loads.push_back({{"from_deg", l.start_rad / degree}, {"to_deg", l.end_rad / degree}, {"force_n", l.force_n}, {"end_force_n", l.ramp ? l.end_force_n : l.force_n}});
  const auto& spring = in.follower.spring;
  j["inputs"] = {{"pitch_radius_mm", in.geometry.pitch_radius_m * 1e3},
                 {"roller_radius_mm", in.geometry.roller_radius_m * 1e3},
                 {"base_radius_mm", (in.geometry.pitch_radius_m - in.geometry.roller_radius_m) * 1e3},
                 {"eccentricity_mm", in.geometry.eccentricity_m * 1e3},
                 {"speed_rpm", in.speed_rad_s / rpm},
                 {"speed_rad_s", in.speed_rad_s},
                 {"mass_kg", in.follower.mass},
                 {"spring_stiffness_n_per_mm", spring.stiffness_n_per_m / 1e3},
                 {"spring_preload_n", spring.preload_n},
                 {"spring_precompression_mm",
                  spring.stiffness_n_per_m > 0.0 ? finite_or_null(spring.preload_n / spring.stiffness_n_per_m * 1e3) : json(nullptr)},
                 {"loads", loads}};

  json table = json::array();
  for (std::size_t i = 0; i < law.pieces().size(); ++i) {
    const auto& p = law.pieces()[i];
    table.push_back({{"index", i},
                     {"law_index", law_index(d.input_case.law_index.at(i))},
                     {"type", cam::segment_type_name(p.segment.type)},
                     {"filler", p.filler},
                     {"start_deg", p.segment.start_rad / degree},
                     {"end_deg", (p.segment.start_rad + p.segment.span_rad) / degree},
                     {"span_deg", p.segment.span_rad / degree},
                     {"lift_mm", p.segment.lift_m * 1e3},
                     {"start_lift_mm", p.start_lift_m * 1e3}});
  }
  j["law"] = table;
  json joints = json::array();
  for (const auto& jt : r.continuity.joints)
    joints.push_back({{"angle_deg", cycle_deg(jt.angle_rad)},
                      {"jump_s_mm", jt.jump_s * 1e3},
                      {"jump_s_d1_mm_per_rad", jt.jump_s_d1 * 1e3},
                      {"jump_s_d2_mm_per_rad2", jt.jump_s_d2 * 1e3},
                      {"jump_s_d3_mm_per_rad3", jt.jump_s_d3 * 1e3}});
  j["continuity"] = {{"summary", r.continuity.summary()},
                     {"lowest_continuous_derivative", r.continuity.lowest_continuous_derivative},
                     {"joints", joints}};

  if (const auto& m = d.input_case.c1_match) {
    j["beta1_deg"] = m->matched_span_rad / degree;
    j["c1_law_index"] = m->c1_law_index;
    j["c1_span_deg"] = m->scene_span_rad / degree;
    j["c1_span_matches_beta1"] = m->scene_span_matches;
  }

  j["alpha_max_deg"] = r.pressure_angle.max.value / degree;
  j["alpha_max_angle_deg"] = cycle_deg(r.pressure_angle.max.angle_rad);
  j["alpha_min_deg"] = r.pressure_angle.min.value / degree;
  j["alpha_min_angle_deg"] = cycle_deg(r.pressure_angle.min.angle_rad);
  j["pressure_angle_limit_deg"] = in.pressure_angle_limit_rad / degree;
  j["pressure_angle_within_limit"] = r.pressure_angle_within_limit;

  json segments = json::array();
  for (const auto& p : r.curvature.pieces) {
    segments.push_back({{"index", p.piece_index},
                        {"law_index", law_index(d.input_case.law_index.at(p.piece_index))},
                        {"type", cam::segment_type_name(p.segment.type)},
                        {"filler", p.filler},
                        {"start_deg", p.segment.start_rad / degree},
                        {"end_deg", (p.segment.start_rad + p.segment.span_rad) / degree},
                        {"rho_pitch_min_mm", p.has_convex ? mm(p.min_positive_rho_m) : json(nullptr)},
                        {"rho_pitch_min_angle_deg", p.has_convex ? cycle_deg(p.angle_min_positive_rad) : json(nullptr)},
                        {"rho_contour_min_mm",
                         p.has_convex ? mm(p.min_positive_rho_m - in.geometry.roller_radius_m) : json(nullptr)},
                        {"rho_pitch_concave_min_mm", p.has_concave ? mm(p.min_concave_abs_rho_m) : json(nullptr)},
                        {"rho_pitch_concave_min_angle_deg",
                         p.has_concave ? cycle_deg(p.angle_min_concave_rad) : json(nullptr)}});
  }
  j["segments"] = segments;
  j["rho_pitch_min_mm"] = mm(r.curvature.min_positive_rho_m);
  j["rho_pitch_min_angle_deg"] = cycle_deg(r.curvature.angle_min_positive_rad);
  j["rho_contour_min_mm"] = mm(r.curvature.min_contour_rho_m);
  j["undercut"] = r.curvature.undercut;

  j["optimal_eccentricity_mm"] = r.optimal_eccentricity.eccentricity_m * 1e3;
  j["optimal_alpha_max_deg"] = r.optimal_eccentricity.alpha.max.value / degree;
  j["optimal_alpha_max_angle_deg"] = cycle_deg(r.optimal_eccentricity.alpha.max.angle_rad);
  j["optimal_alpha_min_deg"] = r.optimal_eccentricity.alpha.min.value / degree;
  j["optimal_alpha_min_angle_deg"] = cycle_deg(r.optimal_eccentricity.alpha.min.angle_rad);

  const auto& cf = r.contact_force;
  j["contact_force_min_n"] = cf.min.contact_force_n;
  j["contact_force_min_angle_deg"] = cycle_deg(cf.min.angle_rad);
  j["contact_force_min_lift_mm"] = cf.min.lift_m * 1e3;
  j["contact_force_max_n"] = cf.max.contact_force_n;
  j["contact_force_max_angle_deg"] = cycle_deg(cf.max.angle_rad);
  j["contact_everywhere"] = cf.contact_everywhere;
  const auto& ns = r.contact_force_without_spring;
  j["contact_force_min_no_spring_n"] = ns.min.contact_force_n;
  j["contact_force_min_no_spring_angle_deg"] = cycle_deg(ns.min.angle_rad);
  j["contact_force_min_no_spring_lift_mm"] = ns.min.lift_m * 1e3;
  j["contact_force_max_no_spring_n"] = ns.max.contact_force_n;
  j["contact_force_max_no_spring_angle_deg"] = cycle_deg(ns.max.angle_rad);
  j["contact_everywhere_no_spring"] = ns.contact_everywhere;

  const auto& ms = r.minimum_spring;
  j["spring_rate_min_n_per_mm"] = ms.feasible ? finite_or_null(ms.min_stiffness_n_per_m / 1e3) : json(nullptr);
  j["spring_rate_min_angle_deg"] = ms.feasible ? cycle_deg(ms.angle_rad) : json(nullptr);
  j["spring_rate_min_lift_mm"] = ms.feasible ? mm(ms.lift_m) : json(nullptr);
  j["spring_rate_min_preload_n"] = spring.preload_n;
  j["spring_rate_feasible"] = ms.feasible;

  j["lift_off_speed_rpm"] = finite_or_null(r.lift_off.speed_rad_s / rpm);
  j["lift_off_angle_deg"] = std::isfinite(r.lift_off.speed_rad_s) ? cycle_deg(r.lift_off.angle_rad) : json(nullptr);
  j["lift_off_lift_mm"] = std::isfinite(r.lift_off.speed_rad_s) ? mm(r.lift_off.lift_m) : json(nullptr);

  const auto& t = r.torque;
  j["mean_torque_nm"] = t.mean_torque_nm;
  j["mean_power_w"] = t.mean_power_w;
  j["torque_max_nm"] = t.max_torque_nm;
  j["torque_max_angle_deg"] = cycle_deg(t.angle_max_torque_rad);
  j["torque_min_nm"] = t.min_torque_nm;
  j["torque_min_angle_deg"] = cycle_deg(t.angle_min_torque_rad);
  j["power_max_w"] = t.max_power_w;
  j["theta_a_min_deg"] = cycle_deg(t.theta_a_min_rad);
  j["a_at_theta_a_min_j"] = t.a_min_j;
  j["theta_a_max_deg"] = cycle_deg(t.theta_a_max_rad);
  j["a_at_theta_a_max_j"] = t.a_max_value_j;
  j["a_max_j"] = t.a_max_j;

  const auto& fw = r.flywheel;
  j["speed_fluctuation"] = in.speed_fluctuation;
  j["flywheel_inertia_kgm2"] = fw.inertia_kgm2;
  j["flywheel_disc_radius_mm"] = fw.disc_radius_m * 1e3;
  j["speed_max_rpm"] = fw.speed_max_rad_s / rpm;
  j["speed_max_angle_deg"] = cycle_deg(fw.theta_speed_max_rad);
  j["speed_min_rpm"] = fw.speed_min_rad_s / rpm;
  j["speed_min_angle_deg"] = cycle_deg(fw.theta_speed_min_rad);

  json events = json::array();
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    const auto& e = r.events[i];
    events.push_back({{"index", i},
                      {"start_deg", cycle_deg(e.start_rad)},
                      {"span_deg", e.span_rad / degree},
                      {"start_lift_mm", e.start_lift_m * 1e3},
                      {"end_lift_mm", e.end_lift_m * 1e3},
                      {"critical", i == r.critical_event}});
  }
  j["events"] = events;
  j["critical_event_index"] = r.critical_event;
  j["critical_event_duration_s"] = r.critical_event_duration_s;
  j["follower_stiffness_n_per_mm"] = r.follower_stiffness_n_per_m / 1e3;
  j["lambda"] = in.lambda;
  j["lambda_multi"] = r.lambda_prime;
  j["damping_ratio"] = in.damping_ratio;

  const auto& sr = r.single_rise;
  j["single_rise_max_error"] = sr.max_error;
  j["single_rise_max_error_tau"] = sr.tau_max_error;
  j["single_rise_residual"] = sr.residual_amplitude;
  j["single_rise_residual_sampled_max"] = sr.max_residual;
  j["single_rise_residual_approx"] = finite_or_null(sr.approx_residual_amplitude);
  j["single_rise_residual_approx_order"] = sr.approx_order;
  j["single_rise_residual_approx_q"] = finite_or_null(sr.approx_q);
  const auto& mr = r.multi_rise;
  j["multi_rise_max_error"] = mr.max_error;
  j["multi_rise_max_error_angle_deg"] = cycle_deg(mr.theta_max_error_rad);
  j["multi_rise_dwell_error"] = mr.max_dwell_error;
  j["multi_rise_cycles"] = mr.cycles;
  j["multi_rise_periodicity_error"] = mr.periodicity_error;
}

void add_flat_face(json& j, const FlatFaceDesign& f, const DesignSettings& s) {
  const auto& p = f.params;
  const auto& a = f.analysis;
  j["inputs"] = {{"lift_mm", p.lift_m * 1e3},
                 {"span_deg", p.span_rad / degree},
                 {"base_radius_mm", p.base_radius_m * 1e3},
                 {"mass_kg", p.mass_kg},
                 {"spring_stiffness_n_per_mm", p.spring_stiffness_n_per_m / 1e3},
                 {"spring_preload_n", p.spring_preload_n},
                 {"spring_precompression_mm", p.spring_preload_n / p.spring_stiffness_n_per_m * 1e3},
                 {"speed_rpm", p.speed_rad_s / rpm},
                 {"speed_rad_s", p.speed_rad_s}};
  j["energy_fluctuation_j"] = a.delta_e_j;
  j["energy_fluctuation_closed_form_j"] = a.delta_e_closed_form_j;
  j["energy_swing_j"] = a.energy_swing_j;
  j["peak_power_w"] = a.peak_power_w;
  j["peak_power_angle_deg"] = cycle_deg(a.angle_peak_power_rad);
  j["mean_torque_nm"] = a.mean_torque_nm;
  j["contact_force_min_n"] = a.min_contact_force_n;
  j["contact_force_min_angle_deg"] = cycle_deg(a.angle_min_contact_force_rad);
  j["contact_everywhere"] = a.contact_everywhere;
  j["contour_curvature_min_mm"] = a.min_curvature_radius_m * 1e3;
  j["offset_max_mm"] = a.max_offset_m * 1e3;
  j["speed_fluctuation"] = s.speed_fluctuation;
  j["flywheel_inertia_kgm2"] = f.flywheel_inertia_kgm2;
  j["flywheel_disc_radius_mm"] = f.flywheel_disc_radius_m * 1e3;
  j["lift_off_speed_rpm"] = finite_or_null(f.lift_off.speed_rad_s / rpm);
  j["lift_off_angle_deg"] = std::isfinite(f.lift_off.speed_rad_s) ? cycle_deg(f.lift_off.angle_rad) : json(nullptr);
  j["lift_off_lift_mm"] = std::isfinite(f.lift_off.speed_rad_s) ? mm(f.lift_off.lift_m) : json(nullptr);
}

}  // namespace

json cycle_deg(double rad) {
  if (!std::isfinite(rad)) return nullptr;
  const double d = std::fmod(rad / degree, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

json report_json(const CamDesignResult& result) {
  json j;
  j["schema_version"] = schema_version;
  j["provenance"] = provenance(result.scene_file);
  j["scene"] = result.scene_name;
  j["overrides"] = result.overrides;
  j["analysis"] = result.flat_face ? "flat_face_follower" : "roller_follower";
  j["settings"] = settings_json(result.settings);
  if (result.roller) add_roller(j, *result.roller);
  if (result.flat_face) add_flat_face(j, *result.flat_face, result.settings);
  return j;
}

}  // namespace mechsim::tools::cam_design
