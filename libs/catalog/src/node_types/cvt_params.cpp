#include "mechsim/catalog/cvt_params.h"

#include <numbers>

namespace mechsim::cosim {

using config::ConfigNode;
namespace dim = config::dim;
namespace cvt = models::cvt;

namespace {

cvt::TaperedBearing parse_bearing(const ConfigNode& b, const cvt::TaperedBearing& d) {
  b.allow_only({"mean_diameter", "axial_factor", "pressure_centre"});
  cvt::TaperedBearing r = d;
  r.mean_diameter = b.positive_quantity_or("mean_diameter", dim::length, d.mean_diameter);
  r.axial_factor = b.positive_quantity_or("axial_factor", dim::dimensionless, d.axial_factor);
  r.pressure_centre = b.non_negative_quantity_or("pressure_centre", dim::length, d.pressure_centre);
  return r;
}

cvt::ShaftBearings parse_shaft(const ConfigNode& s, const cvt::ShaftBearings& d) {
  s.allow_only({"A", "B", "l1", "l2"});
  cvt::ShaftBearings r = d;
  if (auto a = s.optional_child("A")) r.A = parse_bearing(*a, d.A);
  if (auto b = s.optional_child("B")) r.B = parse_bearing(*b, d.B);
  r.l1 = s.positive_quantity_or("l1", dim::length, d.l1);
  r.l2 = s.positive_quantity_or("l2", dim::length, d.l2);
  return r;
}

// A [min, max] pair of quantities.
void parse_range(const ConfigNode& p, std::string_view key, config::Dimension d, double& lo, double& hi) {
  auto r = p.optional_child(key);
  if (!r) return;
  if (!r->is_sequence() || r->size() != 2) r->fail("expected [min, max]");
  const double a = r->at(0).as_quantity(d), b = r->at(1).as_quantity(d);
  if (!(a >= 0.0 && b > a)) r->fail("expected 0 <= min < max");
  lo = a;
  hi = b;
}

// `friction: {disc, ring, link_link, support_ring, support_disc}`.
void parse_friction(const ConfigNode& f, cvt::CvtParams& m) {
  f.allow_only({"disc", "ring", "link_link", "support_ring", "support_disc"});
  m.mu_D = f.positive_quantity_or("disc", dim::dimensionless, m.mu_D);
  m.mu_C = f.positive_quantity_or("ring", dim::dimensionless, m.mu_C);
  m.mu_E = f.non_negative_quantity_or("link_link", dim::dimensionless, m.mu_E);
  m.mu_SUC = f.non_negative_quantity_or("support_ring", dim::dimensionless, m.mu_SUC);
  m.mu_SU = f.non_negative_quantity_or("support_disc", dim::dimensionless, m.mu_SU);
}

// `faces: {disc_thickness, disc_length, ring_thickness, ring_length, support_area}`.
void parse_faces(const ConfigNode& f, cvt::CvtParams& m) {
  f.allow_only({"disc_thickness", "disc_length", "ring_thickness", "ring_length", "support_area"});
  m.t_D = f.positive_quantity_or("disc_thickness", dim::length, m.t_D);
  m.l_D = f.positive_quantity_or("disc_length", dim::length, m.l_D);
  m.t_C = f.positive_quantity_or("ring_thickness", dim::length, m.t_C);
  m.l_C = f.positive_quantity_or("ring_length", dim::length, m.l_C);
  m.A_SU = f.positive_quantity_or("support_area", dim::length.pow(2), m.A_SU);
}

// `numerics: {shape_resolution, push_force_step, angle_convention, code_quirks, round_clamping_force}`.
void parse_numerics(const ConfigNode& n, cvt::CvtParams& m) {
  n.allow_only({"shape_resolution", "push_force_step", "angle_convention", "code_quirks", "round_clamping_force"});
  m.acc = static_cast<int>(n.integer_or("shape_resolution", m.acc));
  if (m.acc < 1 || m.acc > 3) n.child("shape_resolution").fail("expected 1, 2 (the thesis) or 3");
  m.duwproc = n.positive_quantity_or("push_force_step", dim::dimensionless, m.duwproc);
  if (m.duwproc > 1.0) n.child("push_force_step").fail("expected a fraction of T/r in (0, 100 %], e.g. 5 %");
  m.full_angle = n.choice_or("angle_convention", {"full", "half"}, "full") == "full";
  const bool quirks = n.boolean_or("code_quirks", true);
  m.quirk_muSUC_radial = m.quirk_last_sweep_FA = quirks;
  m.round_clamping_force = n.boolean_or("round_clamping_force", m.round_clamping_force);
}

// `clamping: {mode: safety_factor | force, safety_factor, force}`.
void parse_clamping(const ConfigNode& k, CvtConfig& c) {
  k.allow_only({"mode", "safety_factor", "force"});
  const std::string mode = k.choice_or("mode", {"safety_factor", "force"}, "safety_factor");
  if (mode == "force") {
    c.clamp = cvt::ClampMode::clamping_force;
    if (!k.has("force")) k.fail("expected `force` (e.g. 8 kN) with mode: force");
    c.clamping_force = k.non_negative_quantity("force", dim::force);
    if (k.has("safety_factor")) k.child("safety_factor").fail("expected no safety_factor with mode: force");
  } else {
    if (k.has("force")) k.child("force").fail("expected no force with mode: safety_factor");
    c.safety_factor = k.positive_quantity_or("safety_factor", dim::dimensionless, c.safety_factor);
  }
}

// The belt's and the variator's geometry and materials (the top-level keys of params:).
void parse_geometry(const ConfigNode& p, cvt::CvtParams& m) {
  m.lambda = p.choice_or("belt", {"split", "lambda"}, "split") == "split" ? 1 : 2;
  m.disc_driving = p.choice_or("driving", {"intermediate_body", "disc"}, "intermediate_body") == "disc";
  m.r_C = p.positive_quantity_or("neutral_radius", dim::length, m.r_C);
  m.link_thickness = p.positive_quantity_or("link_thickness", dim::length, m.link_thickness);
  m.rocking_radius = p.positive_quantity_or("rocking_radius", dim::length, m.rocking_radius);
  m.l_E = p.positive_quantity_or("rocking_edge_length", dim::length, m.l_E);
  m.closing_angle = p.positive_quantity_or("closing_angle", dim::angle, m.closing_angle);
  m.filling_degree = p.positive_quantity_or("filling_degree", dim::dimensionless, m.filling_degree);
  if (!(m.filling_degree > 0.9 && m.filling_degree < 1.0))
    p.child("filling_degree").fail("expected a belt filling degree in (0.9, 1), e.g. 0.997");
  m.link_mass = p.non_negative_quantity_or("link_mass", dim::mass, m.link_mass);
  m.beta_D = p.positive_quantity_or("disc_cone_angle", dim::angle, m.beta_D);
  m.beta_C = p.positive_quantity_or("ring_cone_angle", dim::angle, m.beta_C);
  for (const char* k : {"disc_cone_angle", "ring_cone_angle"})
    if (p.has(k) && p.quantity(k, dim::angle) >= std::numbers::pi / 2) p.child(k).fail("expected a cone angle below 90 deg");
}

}  // namespace

CvtConfig parse_cvt_config(const ConfigNode& p, const std::vector<std::string>& other_keys) {
  std::vector<std::string> keys{"belt", "driving", "neutral_radius", "link_thickness", "rocking_radius",
                                "rocking_edge_length", "closing_angle", "filling_degree", "link_mass",
                                "disc_cone_angle", "ring_cone_angle", "friction", "faces", "admissible_stress",
                                "reduced_modulus", "curvature_design_radii", "bearings", "validated_range",
                                "numerics", "clamping", "level"};
  keys.insert(keys.end(), other_keys.begin(), other_keys.end());
  p.allow_only(keys);
  CvtConfig c;
  cvt::CvtParams& m = c.params;
  parse_geometry(p, m);
  if (auto f = p.optional_child("friction")) parse_friction(*f, m);
  if (auto f = p.optional_child("faces")) parse_faces(*f, m);
  m.sigma_admissible = p.positive_quantity_or("admissible_stress", dim::pressure, m.sigma_admissible);
  m.E_R = p.positive_quantity_or("reduced_modulus", dim::pressure, m.E_R);
  if (auto r = p.optional_child("curvature_design_radii")) {
    if (!r->is_sequence() || r->size() != 2) r->fail("expected two disc radii [r_D min, r_D max], e.g. [45 mm, 95 mm]");
    for (std::size_t i = 0; i < 2; ++i) {
      m.r_D_design[i] = r->at(i).as_quantity(dim::length);
      if (!(m.r_D_design[i] > 0)) r->at(i).fail("expected a radius > 0");
    }
  }
  if (auto b = p.optional_child("bearings")) {
    b->allow_only({"primary", "secondary", "grease_viscosity"});
    if (auto s = b->optional_child("primary")) m.primary = parse_shaft(*s, m.primary);
    if (auto s = b->optional_child("secondary")) m.secondary = parse_shaft(*s, m.secondary);
    m.grease_viscosity = b->positive_quantity_or("grease_viscosity", dim::kinematic_viscosity, m.grease_viscosity);
  }
  if (auto v = p.optional_child("validated_range")) {
    v->allow_only({"ratio_setting", "torque", "speed"});
    parse_range(*v, "ratio_setting", dim::length, m.s_min, m.s_max);
    parse_range(*v, "torque", dim::torque, m.torque_min, m.torque_max);
    parse_range(*v, "speed", dim::angular_velocity, m.speed_min, m.speed_max);
  }
  if (auto n = p.optional_child("numerics")) parse_numerics(*n, m);
  if (auto k = p.optional_child("clamping")) parse_clamping(*k, c);
  c.level = p.choice_or("level", {"L1", "L0"}, "L1") == "L0" ? cvt::Level::L0 : cvt::Level::L1;
  return c;
}

}  // namespace mechsim::cosim
