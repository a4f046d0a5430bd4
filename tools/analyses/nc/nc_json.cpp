#include "nc_json.h"

#include <cmath>

#include "json_io.h"
#include "mechsim/models/constants.h"
#include "provenance.h"

namespace mechsim::tools::nc_analyses {

namespace nc = models::nc;
using nlohmann::json;

namespace {

using models::two_pi;

json optional_number(const std::optional<double>& v) { return v ? finite_or_null(*v) : json(nullptr); }
// Relative deviation of an approximation from the exact value [%].
json error_percent(double approx, const std::optional<double>& exact) {
  return exact ? finite_or_null(100 * (approx - *exact) / *exact) : json(nullptr);
}

json header(const std::string& command, const std::string& scene_name, const std::string& scene_file,
            const std::vector<std::string>& overrides) {
  return {{"schema_version", schema_version},
          {"command", command},
          {"provenance", provenance(scene_file)},
          {"scene", {{"name", scene_name}, {"file", scene_file}}},
          {"overrides", overrides}};
}

json source_json(const DataSource& s) {
  return {{"kind", s.kind}, {"key_path", s.where.empty() ? json(nullptr) : json(s.where)}};
}

json motor_parameters(const nc::MotorTachoParams& p) {
  return {{"armature_resistance_ohm", p.armature_resistance},
          {"armature_inductance_h", p.armature_inductance},
          {"torque_constant_nm_per_a", p.torque_constant},
          {"tacho_constant_v_s_per_rad", p.tacho_constant},
          {"rotor_inertia_kgm2", p.motor_inertia},
          {"tacho_inertia_kgm2", p.tacho_inertia},
          {"shaft_stiffness_nm_per_rad", p.shaft_stiffness},
          {"rotor_damping_nms_per_rad", p.motor_damping},
          {"tacho_damping_nms_per_rad", p.tacho_damping},
          {"shaft_damping_nms_per_rad", p.shaft_damping}};
}

json poles_json(const std::array<std::complex<double>, 4>& poles) {
  json out = json::array();
  for (const auto& p : poles)
    out.push_back({{"re", p.real()}, {"im", p.imag()}, {"f_hz", std::abs(p) / two_pi}, {"damping", -p.real() / std::abs(p)}});
  return out;
}

// The frequency-domain figures of one parameter set (flat, for the nominal set and the
// variants alike).
void add_response(json& j, const MotorTachoAnalysis& a) {
  j["dc_gain"] = a.dc_gain;
  j["corner_hz"] = a.corner_hz;
  j["resonance_hz"] = a.resonance ? json(a.resonance->frequency_hz) : json(nullptr);
  j["peak_db"] = a.resonance ? json(a.resonance->peak_height_db) : json(nullptr);
  j["natural_frequency_hz"] = a.resonance ? json(a.resonance->natural_frequency_hz) : json(nullptr);
  j["damping_ratio"] = a.resonance ? json(a.resonance->damping_ratio) : json(nullptr);
  j["resonance_is_local_maximum"] = a.resonance ? json(a.resonance->is_local_maximum) : json(nullptr);
  j["stiffness_ratio"] = a.stiffness_ratio;
  j["real_part_ratio"] = a.real_part_ratio;
}

json settings_json(const MotorBodeSettings& s) {
  return {{"frequency_range_hz", {s.frequency_from_hz, s.frequency_to_hz}},
          {"points_per_decade", s.points_per_decade},
          {"shaft_damping_variants_nms_per_rad", s.shaft_damping_variants},
          {"load_inertia_kgm2", s.load_inertia ? json(*s.load_inertia) : json(nullptr)}};
}

json settings_json(const SlideModesSettings& s) {
  return {{"slide_position_mm", s.slide_position ? json(*s.slide_position * 1e3) : json(nullptr)},
          {"ritz_shapes", s.ritz_shapes},
          {"lump_coupling_inertia", s.lump_coupling_inertia},
          {"position_points", s.position_points},
          {"diameter_range_mm", {s.diameter_from * 1e3, s.diameter_to * 1e3}},
          {"diameter_points", s.diameter_points},
          {"ritz_convergence", s.ritz_convergence},
          {"fe_convergence", s.fe_convergence},
          {"sweep_fe_elements", s.sweep_fe_elements}};
}

json convergence_json(const std::vector<ConvergencePoint>& points, const char* count_key) {
  json out = json::array();
  for (const auto& p : points) out.push_back({{count_key, p.count}, {"f0_hz", p.frequency_hz}});
  return out;
}

}  // namespace

json motor_bode_json(const MotorBodeResult& r) {
  const MotorTachoAnalysis& n = r.nominal;
  json j = header("motor-bode", r.scene_name, r.scene_file, r.overrides);
  j["source"] = source_json(r.motor.source);
  j["notes"] = r.motor.notes;
  j["parameters"] = motor_parameters(r.motor.params);
  j["settings"] = settings_json(r.settings);
  const nc::TransferFunction& g = n.transfer_function;
  j["coefficients"] = {{"m1", g.m1}, {"m0", g.m0}, {"n4", g.n4}, {"n3", g.n3}, {"n2", g.n2}, {"n1", g.n1}, {"n0", g.n0}};
  j["poles"] = poles_json(n.poles);
  add_response(j, n);

  // The report's approximations (3)-(5) next to the exact poles they stand for.
  const nc::PoleApproximations& ap = n.approximations;
  j["approx_s1_hz"] = ap.slow_pole_hz;
  j["approx_s2_hz"] = ap.electrical_pole_hz;
  j["approx_f0_hz"] = ap.resonance_hz;
  j["exact_s1_hz"] = optional_number(n.exact_slow_pole_hz);
  j["exact_s2_hz"] = optional_number(n.exact_electrical_pole_hz);
  j["exact_f0_hz"] = optional_number(n.exact_shaft_pair_hz);
  j["approximations"] = json::array(
      {{{"name", "s1"}, {"equation", "(3)"}, {"formula", "c^2/(R_a (I1 + I2))/2pi"}, {"approx_hz", ap.slow_pole_hz},
        {"exact_hz", optional_number(n.exact_slow_pole_hz)},
        {"error_percent", error_percent(ap.slow_pole_hz, n.exact_slow_pole_hz)}},
       {{"name", "s2"}, {"equation", "(4)"}, {"formula", "R_a/L_a/2pi"}, {"approx_hz", ap.electrical_pole_hz},
        {"exact_hz", optional_number(n.exact_electrical_pole_hz)},
        {"error_percent", error_percent(ap.electrical_pole_hz, n.exact_electrical_pole_hz)}},
       {{"name", "f0"}, {"equation", "(5), k inside the root"}, {"formula", "sqrt(k (I1 + I2)/(I1 I2))/2pi"},
        {"approx_hz", ap.resonance_hz}, {"exact_hz", optional_number(n.exact_shaft_pair_hz)},
        {"error_percent", error_percent(ap.resonance_hz, n.exact_shaft_pair_hz)}}});

  json variants = json::array();
  for (const auto& v : r.shaft_damping_variants) {
    json e = {{"b3", v.params.shaft_damping}};
    add_response(e, v);
    variants.push_back(e);
  }
  j["b3_variants"] = variants;

  json load = {{"inertia_kgm2", r.load_inertia},
               {"source", r.load_inertia_source},
               {"rotor_inertia_with_load_kgm2", r.with_load.params.motor_inertia}};
  add_response(load, r.with_load);
  load["poles"] = poles_json(r.with_load.poles);
  load["approx_f0_hz"] = r.with_load.approximations.resonance_hz;
  j["load_inertia"] = load;
  return j;
}

json slide_modes_json(const SlideModesResult& r) {
  const nc::SlideDriveData& d = r.slide.data;
  json j = header("slide-modes", r.scene_name, r.scene_file, r.overrides);
  j["source"] = source_json(r.slide.source);
  j["coupling_stiffness_source"] = source_json(r.slide.coupling_stiffness_source);
  j["notes"] = r.slide.notes;
  j["inputs"] = {{"slide_mass_kg", d.slide_mass},
                 {"spindle_diameter_mm", d.spindle_diameter * 1e3},
                 {"lead_mm", d.lead * 1e3},
                 {"spindle_length_mm", d.spindle_length * 1e3},
                 {"density_kg_per_m3", d.density},
                 {"shear_modulus_pa", d.shear_modulus},
                 {"coupling_inertia_kgm2", d.coupling_inertia},
                 {"coupling_stiffness_nm_per_rad", d.coupling_stiffness},
                 {"slide_inertia_kgm2", d.slide_inertia()},
                 {"slide_inertia_from", d.slide_inertia_override ? "given" : "m s^2/(4 pi^2)"}};
  j["derived"] = {{"spindle_inertia_kgm2", d.spindle_inertia()},
                  {"spindle_stiffness_nm_per_rad", d.spindle_stiffness()},
                  {"coupling_equivalent_length_mm", d.coupling_equivalent_length() * 1e3},
                  {"rigid_inertia_kgm2", d.coupling_inertia + d.spindle_inertia() + d.slide_inertia()},
                  {"model1_drive_end_inertia_kgm2", d.coupling_inertia + d.spindle_inertia() / 2},
                  {"model1_slide_end_inertia_kgm2", d.slide_inertia() + d.spindle_inertia() / 2},
                  {"model1_series_stiffness_nm_per_rad",
                   d.coupling_stiffness * d.spindle_stiffness() / (d.coupling_stiffness + d.spindle_stiffness())}};
  j["settings"] = settings_json(r.settings);

  j["slide_position_mm"] = r.slide_position * 1e3;
  j["f0_model1_hz"] = r.model1_hz;
  j["f0_model2_hz"] = {r.model2.first_hz, r.model2.second_hz};
  j["f0_model3_hz"] = r.model3_hz;
  j["f0_model3_ritz_shapes"] = r.settings.ritz_shapes;
  j["f0_model3_converged_hz"] = r.model3_converged_hz;
  j["f0_model3_converged_fe_elements"] = r.settings.fe_convergence.back();
  j["f0_model3_extrapolated_hz"] = optional_number(r.model3_extrapolated_hz);
  j["model3_convergence"] = {{"slide_position_mm", r.slide_position * 1e3},
                             {"ritz", convergence_json(r.ritz_convergence, "shapes")},
                             {"fe", convergence_json(r.fe_convergence, "elements")}};

  json positions = json::array();
  for (const auto& p : r.f0_vs_position)
    positions.push_back({{"position_mm", p.position * 1e3}, {"f0_hz", p.ritz_hz}, {"f0_converged_hz", p.converged_hz}});
  j["f0_vs_position"] = positions;
  j["f0_max"] = {{"position_mm", r.f0_max.position * 1e3}, {"f0_hz", r.f0_max.ritz_hz},
                 {"f0_converged_hz", r.f0_max.converged_hz}};
  j["first_mode_node"] = r.first_mode_node ? json{{"position_mm", r.first_mode_node->position * 1e3},
                                                  {"f0_hz", r.first_mode_node->frequency_hz}}
                                           : json(nullptr);
  json diameters = json::array();
  for (const auto& p : r.f0_vs_diameter)
    diameters.push_back({{"diameter_mm", p.diameter * 1e3},
                         {"f0_model1_hz", p.model1_hz},
                         {"f0_model2_hz", {p.model2.first_hz, p.model2.second_hz}},
                         {"f0_model3_hz", p.model3_hz},
                         {"f0_model3_converged_hz", p.model3_converged_hz},
                         {"coupling_equivalent_length_mm", p.coupling_equivalent_length * 1e3}});
  j["f0_vs_diameter"] = diameters;
  return j;
}

}  // namespace mechsim::tools::nc_analyses
