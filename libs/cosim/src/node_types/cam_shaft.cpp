// Node type `cam_shaft`: the cam shaft with its motion law and pitch-curve geometry,
// publishing <name>/state (CamState). Reads the follower's drive torque.
#include <numbers>

#include "mechsim/cosim/catalog.h"
#include "mechsim/cosim/node_params.h"
#include "mechsim/models/cam/cam_shaft_block.h"

namespace mechsim::cosim {

namespace cam = models::cam;
using config::ConfigNode;
namespace dim = config::dim;

cam::MotionLaw parse_motion_law(const ConfigNode& law) {
  if (!law.is_sequence() || law.size() == 0)
    law.fail("expected a list of segments {type, start, span, lift}");
  std::vector<cam::Segment> segments;
  std::vector<std::string> types;
  for (auto t : {cam::SegmentType::full_cycloid, cam::SegmentType::half_cycloid_c1, cam::SegmentType::half_cycloid_c2,
                 cam::SegmentType::dwell, cam::SegmentType::harmonic, cam::SegmentType::polynomial_345,
                 cam::SegmentType::modified_sine, cam::SegmentType::modified_trapezoid,
                 cam::SegmentType::constant_velocity})
    types.push_back(cam::segment_type_name(t));
  for (std::size_t i = 0; i < law.size(); ++i) {
    ConfigNode s = law.at(i);
    s.allow_only({"type", "start", "span", "lift"});
    cam::Segment seg;
    seg.type = cam::segment_type_from_name(s.choice("type", types));
    seg.start_rad = s.quantity("start", dim::angle);
    seg.span_rad = s.positive_quantity("span", dim::angle);
    seg.lift_m = seg.type == cam::SegmentType::dwell ? s.quantity_or("lift", dim::length, 0.0)
                                                     : s.quantity("lift", dim::length);
    segments.push_back(seg);
  }
  try {
    cam::MotionLaw result(std::move(segments));
    if (result.continuity().velocity_jumps())
      law.fail("expected a law with continuous velocity S' (" + result.continuity().summary() +
               "): a velocity jump means infinite acceleration");
    return result;
  } catch (const std::invalid_argument& e) {
    law.fail(std::string("expected a valid motion law: ") + e.what());
  }
}

cam::CamShaftParams parse_cam_shaft_params(const ConfigNode& p) {
  p.allow_only({"speed", "pitch_radius", "eccentricity", "initial_angle", "law"});
  cam::CamShaftParams params{parse_motion_law(p.child("law")), p.positive_quantity("pitch_radius", dim::length),
                             p.quantity_or("eccentricity", dim::length, 0.0), p.positive_quantity("speed", dim::angular_velocity),
                             p.quantity_or("initial_angle", dim::angle, 0.0)};
  if (std::abs(params.eccentricity) >= params.pitch_radius)
    p.child("eccentricity").fail("expected |eccentricity| below the pitch radius");
  return params;
}

namespace {

std::unique_ptr<models::Block> make_cam_shaft(const ConfigNode& p) {
  return std::make_unique<cam::CamShaftBlock>(parse_cam_shaft_params(p));
}

}  // namespace

NodeType cam_shaft_node_type() {
  return {"cam_shaft",
          "cam shaft: constant-speed drive, motion law, pressure angle; publishes CamState",
          transport::find_topic_type("CamState"),
          "state",
          make_cam_shaft,
          {{transport::find_topic_type("FollowerState"), {{"drive_torque", "load_torque"}}}}};
}

}  // namespace mechsim::cosim
