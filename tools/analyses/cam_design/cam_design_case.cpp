#include "cam_design_case.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "mechsim/catalog/node_params.h"
#include "mechsim/models/constants.h"

namespace mechsim::tools::cam_design {

namespace cam = models::cam;
using config::ConfigNode;
namespace dim = config::dim;

namespace {

using models::degree;

// One entry of the scene's `law:` list as written (before the law is built).
struct RawSegment {
  std::size_t index;
  std::string type;
  double start_rad, span_rad, lift_m;
};

std::vector<RawSegment> raw_segments(const ConfigNode& law) {
  std::vector<RawSegment> out;
  if (!law.is_sequence()) return out;
  for (std::size_t i = 0; i < law.size(); ++i) {
    const ConfigNode s = law.at(i);
    out.push_back({i, s.string("type"), s.quantity("start", dim::angle), s.quantity("span", dim::angle),
                   s.has("lift") ? s.quantity("lift", dim::length) : 0.0});
  }
  return out;
}

// The first C1 in angle order and the segment after it (cyclically); refuses a law
// without that pair at design.match_c1_to_c2.
C1Match match_first_c1(const std::vector<RawSegment>& raw, const ConfigNode& flag_node) {
  std::vector<RawSegment> sorted = raw;
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.start_rad < b.start_rad; });
  const auto c1 = std::find_if(sorted.begin(), sorted.end(), [](const auto& s) { return s.type == "half_cycloid_c1"; });
  if (c1 == sorted.end()) flag_node.fail("expected a law with a half_cycloid_c1 segment to match (or false)");
  const auto next = std::next(c1) == sorted.end() ? sorted.begin() : std::next(c1);
  if (next->type != "half_cycloid_c2")
    flag_node.fail("expected the first half_cycloid_c1 (law[" + std::to_string(c1->index) +
                   "]) to be followed by a half_cycloid_c2, found " + next->type + " (law[" +
                   std::to_string(next->index) + "])");
  C1Match m{};
  m.c1_law_index = c1->index;
  m.c2_law_index = next->index;
  m.matched_span_rad = cam::matched_c1_span(c1->lift_m, next->span_rad, next->lift_m);
  m.scene_span_rad = c1->span_rad;
  m.scene_span_matches = std::abs(m.matched_span_rad - m.scene_span_rad) < 1e-6 * degree;
  return m;
}

std::string format_deg(double rad) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g deg", rad / degree);
  return buf;
}

// The cam_shaft parameters. A C1 whose span does not match its C2 is refused by the law
// for its velocity jump; when the scene asks for the match, the refusal says which span
// would have been right.
cam::CamShaftParams parse_shaft(const ConfigNode& cam_params, const std::optional<ConfigNode>& flag_node) {
  try {
    return cosim::parse_cam_shaft_params(cam_params);
  } catch (const config::ConfigError& e) {
    if (!flag_node) throw;
    std::optional<C1Match> m;
    try {
      m = match_first_c1(raw_segments(cam_params.child("law")), *flag_node);
    } catch (const config::ConfigError&) {
      throw e;
    }
    if (m->scene_span_matches) throw;
    throw config::ConfigError(e.file(), e.key_path(),
                              e.expected() + " (design.match_c1_to_c2: the C1 at law[" +
                                  std::to_string(m->c1_law_index) + "] needs a span of " +
                                  format_deg(m->matched_span_rad) + ", not " + format_deg(m->scene_span_rad) + ")",
                              e.line());
  }
}

}  // namespace

RollerCase roller_case_from_scene(const config::Scene& scene, const DesignSettings& settings) {
  const config::ParticipantSpec* cam_spec = nullptr;
  const config::ParticipantSpec* follower_spec = nullptr;
  int cams = 0, followers = 0;
  for (const auto& p : scene.participants) {
    if (p.type == "cam_shaft" && cams++ == 0) cam_spec = &p;
    if (p.type == "follower" && followers++ == 0) follower_spec = &p;
  }
  if (!cam_spec || !follower_spec)
    scene.root.child("participants")
        .fail(std::string("expected a cam_shaft and a follower participant for the roller-follower design "
                          "(or design.follower: flat_face); missing: ") +
              (!cam_spec ? "cam_shaft" : "follower"));

  RollerCase c;
  c.cam_participant = cam_spec->name;
  c.follower_participant = follower_spec->name;
  if (cams > 1)
    c.notes.push_back(std::to_string(cams) + " cam_shaft participants: the first ('" + cam_spec->name + "') is analysed");
  if (followers > 1)
    c.notes.push_back(std::to_string(followers) + " follower participants: the first ('" + follower_spec->name +
                      "') is analysed");

  const ConfigNode& cam_params = cam_spec->params;
  std::optional<ConfigNode> flag_node;
  if (settings.match_c1_to_c2) flag_node = scene.design->child("match_c1_to_c2");

  const cam::CamShaftParams shaft = parse_shaft(cam_params, flag_node);
  const cosim::FollowerConfig follower = cosim::parse_follower_params(follower_spec->params);

  const std::vector<RawSegment> raw = raw_segments(cam_params.child("law"));
  if (flag_node) c.c1_match = match_first_c1(raw, *flag_node);
  for (const auto& piece : shaft.law.pieces()) {
    std::optional<std::size_t> index;
    if (!piece.filler) {
      for (const auto& r : raw)
        if (std::abs(r.start_rad - piece.segment.start_rad) < 1e-12 &&
            r.type == cam::segment_type_name(piece.segment.type))
          index = r.index;
    }
    c.law_index.push_back(index);
  }

  cam::CamDesignInput& in = c.input;
  in.segments = shaft.law.segments();
  in.geometry = {shaft.pitch_radius, follower.roller_radius, shaft.eccentricity};
  in.speed_rad_s = shaft.speed;
  in.follower = follower.params;
  in.pressure_angle_limit_rad = settings.pressure_angle_limit_rad;
  in.speed_fluctuation = settings.speed_fluctuation;
  in.flywheel_density_kg_m3 = settings.flywheel_density_kg_m3;
  in.flywheel_thickness_m = settings.flywheel_thickness_m;
  in.lambda = settings.lambda;
  in.damping_ratio = settings.damping_ratio;
  in.multi_rise_cycles = settings.multi_rise_cycles;
  if (!(follower.roller_radius < shaft.pitch_radius))
    follower_spec->params.child("roller_radius")
        .fail("expected a roller radius below the cam's pitch radius (" + std::to_string(shaft.pitch_radius * 1e3) +
              " mm): the base circle R0 - Rr must be positive");
  if (follower.roller_radius == 0.0)
    c.notes.push_back("roller_radius not given: a point follower (the cam contour is the pitch curve)");
  return c;
}

}  // namespace mechsim::tools::cam_design
