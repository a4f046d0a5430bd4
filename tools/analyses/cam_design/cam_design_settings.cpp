#include "cam_design_settings.h"

#include <stdexcept>

namespace mechsim::tools::cam_design {

using config::ConfigNode;
namespace dim = config::dim;

namespace {

models::cam::FlatFaceParams parse_flat_face(const ConfigNode& f) {
  if (!f.is_map()) f.fail("expected a map {lift, span, base_radius, mass, stiffness, preload, speed}");
  f.allow_only({"lift", "span", "base_radius", "mass", "stiffness", "preload", "speed"});
  models::cam::FlatFaceParams p{};
  p.lift_m = f.positive_quantity("lift", dim::length);
  p.span_rad = f.positive_quantity("span", dim::angle);
  if (2.0 * p.span_rad > 2.0 * std::numbers::pi * (1.0 + 1e-12))
    f.child("span").fail("expected a span of at most 180 deg: the return takes another span in the same turn");
  p.base_radius_m = f.positive_quantity("base_radius", dim::length);
  p.mass_kg = f.positive_quantity("mass", dim::mass);
  // k > 0: the preload is given as a force k x0, and x0 = F0/k is needed for the force law.
  p.spring_stiffness_n_per_m = f.positive_quantity("stiffness", dim::stiffness);
  p.spring_preload_n = f.non_negative_quantity("preload", dim::force);
  p.speed_rad_s = f.positive_quantity("speed", dim::angular_velocity);
  return p;
}

}  // namespace

DesignSettings parse_design_settings(const std::optional<ConfigNode>& design) {
  DesignSettings s;
  if (!design) return s;
  const ConfigNode& d = *design;
  if (!d.is_map()) d.fail("expected a map of cam-design settings (speed_fluctuation, flywheel, lambda, ...)");
  d.allow_only({"speed_fluctuation", "flywheel", "lambda", "damping_ratio", "multi_rise_cycles",
                "pressure_angle_limit", "match_c1_to_c2", "follower", "flat_face"});

  if (d.has("speed_fluctuation")) {
    s.speed_fluctuation = d.number("speed_fluctuation");
    // K < 2 keeps ω_min = ω_avg (1 − K/2) positive.
    if (!(s.speed_fluctuation > 0.0 && s.speed_fluctuation < 2.0))
      d.child("speed_fluctuation").fail("expected a speed fluctuation coefficient in (0, 2), e.g. 0.1 or '10 %'");
  }
  if (auto fw = d.optional_child("flywheel")) {
    if (!fw->is_map()) fw->fail("expected a map {density, thickness}");
    fw->allow_only({"density", "thickness"});
    s.flywheel_density_kg_m3 = fw->positive_quantity_or("density", dim::density, s.flywheel_density_kg_m3);
    s.flywheel_thickness_m = fw->positive_quantity_or("thickness", dim::length, s.flywheel_thickness_m);
  }
  if (d.has("lambda")) {
    s.lambda = d.number("lambda");
    if (!(s.lambda > 0.0)) d.child("lambda").fail("expected a positive number of natural periods, e.g. 9.38");
  }
  if (d.has("damping_ratio")) {
    s.damping_ratio = d.number("damping_ratio");
    // The residual-vibration envelope uses the damped frequency: underdamped only.
    if (!(s.damping_ratio >= 0.0 && s.damping_ratio < 1.0))
      d.child("damping_ratio").fail("expected a damping ratio in [0, 1), e.g. 0.08");
  }
  if (d.has("multi_rise_cycles")) {
    const long n = d.integer("multi_rise_cycles");
    // At least two cycles: the periodicity check compares the last one with the one before.
    if (n < 2 || n > 10000) d.child("multi_rise_cycles").fail("expected a number of cycles in 2..10000, e.g. 20");
    s.multi_rise_cycles = static_cast<int>(n);
  }
  if (d.has("pressure_angle_limit")) {
    s.pressure_angle_limit_rad = d.positive_quantity("pressure_angle_limit", dim::angle);
    if (!(s.pressure_angle_limit_rad < std::numbers::pi / 2))
      d.child("pressure_angle_limit").fail("expected an angle below 90 deg, e.g. '30 deg'");
  }
  s.match_c1_to_c2 = d.boolean_or("match_c1_to_c2", false);
  s.follower = d.choice_or("follower", {"roller", "flat_face"}, "roller") == "flat_face" ? FollowerKind::flat_face
                                                                                        : FollowerKind::roller;
  if (s.follower == FollowerKind::flat_face) {
    s.flat_face = parse_flat_face(d.child("flat_face"));
    if (s.match_c1_to_c2)
      d.child("match_c1_to_c2").fail("expected false: the flat-faced follower's law has no C1/C2 pair");
  } else if (d.has("flat_face")) {
    d.child("flat_face").fail("expected no flat_face section unless 'follower: flat_face'");
  }
  return s;
}

}  // namespace mechsim::tools::cam_design
