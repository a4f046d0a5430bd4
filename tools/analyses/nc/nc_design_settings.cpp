#include "nc_design_settings.h"

#include <string>
#include <tuple>
#include <utility>

namespace mechsim::tools::nc_analyses {

using config::ConfigNode;
namespace dim = config::dim;

namespace {

// [from, to] as a two-element list of quantities, from < to, both > 0.
std::pair<double, double> parse_range(const ConfigNode& node, config::Dimension d, const std::string& example) {
  if (!node.is_sequence() || node.size() != 2) node.fail("expected a range [from, to], e.g. " + example);
  const double from = node.at(0).as_quantity(d), to = node.at(1).as_quantity(d);
  if (!(from > 0.0)) node.at(0).fail("expected a positive start of the range, e.g. " + example);
  if (!(to > from)) node.at(1).fail("expected the end of the range above its start, e.g. " + example);
  return {from, to};
}

int parse_count(const ConfigNode& parent, std::string_view key, int default_value, int min, int max) {
  if (!parent.has(key)) return default_value;
  const long n = parent.integer(key);
  if (n < min || n > max)
    parent.child(key).fail("expected a whole number in " + std::to_string(min) + ".." + std::to_string(max));
  return static_cast<int>(n);
}

// A strictly ascending list of whole numbers in [min, max].
std::vector<int> parse_counts(const ConfigNode& node, int min, int max, const std::string& example) {
  if (!node.is_sequence() || node.size() == 0) node.fail("expected a list of whole numbers, e.g. " + example);
  std::vector<int> counts;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const long n = node.at(i).as_integer();
    if (n < min || n > max)
      node.at(i).fail("expected a whole number in " + std::to_string(min) + ".." + std::to_string(max));
    if (!counts.empty() && n <= counts.back()) node.at(i).fail("expected an ascending list, e.g. " + example);
    counts.push_back(static_cast<int>(n));
  }
  return counts;
}

MotorBodeSettings parse_motor_bode(const ConfigNode& m) {
  if (!m.is_map()) m.fail("expected a map {frequency_range, points_per_decade, shaft_damping_variants, load_inertia}");
  m.allow_only({"frequency_range", "points_per_decade", "shaft_damping_variants", "load_inertia"});
  MotorBodeSettings s;
  if (auto r = m.optional_child("frequency_range"))
    std::tie(s.frequency_from_hz, s.frequency_to_hz) = parse_range(*r, dim::frequency, "[1 Hz, 10 kHz]");
  s.points_per_decade = parse_count(m, "points_per_decade", s.points_per_decade, 10, 2000);
  if (auto v = m.optional_child("shaft_damping_variants")) {
    if (!v->is_sequence() || v->size() == 0)
      v->fail("expected a list of shaft dampings b3, e.g. [1e-4 N m s/rad, 1e-2 N m s/rad, 1e-1 N m s/rad]");
    s.shaft_damping_variants.clear();
    for (std::size_t i = 0; i < v->size(); ++i) {
      const double b3 = v->at(i).as_quantity(dim::rotational_damping);
      if (!(b3 >= 0.0)) v->at(i).fail("expected a shaft damping >= 0, e.g. '1e-2 N m s/rad'");
      s.shaft_damping_variants.push_back(b3);
    }
  }
  if (m.has("load_inertia")) s.load_inertia = m.non_negative_quantity("load_inertia", dim::inertia);
  return s;
}

SlideModesSettings parse_slide_modes(const ConfigNode& m) {
  if (!m.is_map())
    m.fail("expected a map {slide_position, ritz_shapes, lump_coupling_inertia, position_points, diameter_range, "
           "diameter_points, ritz_convergence, fe_convergence, sweep_fe_elements}");
  m.allow_only({"slide_position", "ritz_shapes", "lump_coupling_inertia", "position_points", "diameter_range",
                "diameter_points", "ritz_convergence", "fe_convergence", "sweep_fe_elements"});
  SlideModesSettings s;
  if (m.has("slide_position")) {
    s.slide_position = m.non_negative_quantity("slide_position", dim::length);
    s.slide_position_node = m.child("slide_position");
  }
  // Ritz needs n = 0 (rigid) and n = 1 for a non-rigid mode; the upper limits keep the
  // dense eigenproblems small.
  s.ritz_shapes = parse_count(m, "ritz_shapes", s.ritz_shapes, 2, 200);
  s.lump_coupling_inertia = m.boolean_or("lump_coupling_inertia", s.lump_coupling_inertia);
  s.position_points = parse_count(m, "position_points", s.position_points, 2, 10000);
  if (auto r = m.optional_child("diameter_range"))
    std::tie(s.diameter_from, s.diameter_to) = parse_range(*r, dim::length, "[31 mm, 39 mm]");
  s.diameter_points = parse_count(m, "diameter_points", s.diameter_points, 2, 10000);
  if (auto r = m.optional_child("ritz_convergence")) s.ritz_convergence = parse_counts(*r, 2, 200, "[2, 4, 8, 16, 32]");
  // At least 2 elements: the slide's node splits the chain into up to two segments (a
  // coupling inertia lumped at the drive end sits on the end node), one element each.
  if (auto r = m.optional_child("fe_convergence"))
    s.fe_convergence = parse_counts(*r, 2, 100000, "[8, 16, 32, 64, 128]");
  s.sweep_fe_elements = parse_count(m, "sweep_fe_elements", s.sweep_fe_elements, 2, 100000);
  return s;
}

}  // namespace

NcDesignSettings parse_nc_design_settings(const std::optional<ConfigNode>& design) {
  NcDesignSettings s;
  if (!design) return s;
  const ConfigNode& d = *design;
  if (!d.is_map()) d.fail("expected a map of NC analysis settings (motor, slide, motor_bode, slide_modes)");
  d.allow_only({"motor", "slide", "motor_bode", "slide_modes"});
  s.motor = d.optional_child("motor");
  s.slide = d.optional_child("slide");
  if (s.motor && !s.motor->is_map()) s.motor->fail("expected a map of motor-tacho parameters (as a tachometer's params)");
  if (s.slide && !s.slide->is_map()) s.slide->fail("expected a map of slide drive data (as a slide's params)");
  if (auto m = d.optional_child("motor_bode")) s.motor_bode = parse_motor_bode(*m);
  if (auto m = d.optional_child("slide_modes")) s.slide_modes = parse_slide_modes(*m);
  return s;
}

}  // namespace mechsim::tools::nc_analyses
