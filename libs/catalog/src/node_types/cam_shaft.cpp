// Node type `cam_shaft`: the cam shaft with its motion law, pitch-curve geometry and drive,
// publishing <name>/state (CamState). Reads the follower's drive torque and reflected inertia,
// and on a line shaft the upstream shaft's motion and the downstream segment's torque.
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "mechsim/catalog/catalog.h"
#include "mechsim/catalog/node_params.h"
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

namespace {

// `drive:` (default constant speed) and, for a torque drive, the shaft inertia.
void parse_drive(const ConfigNode& p, cam::CamShaftParams& params) {
  const std::optional<ConfigNode> drive = p.optional_child("drive");
  if (drive && !drive->is_map())
    drive->fail("expected a map {type: constant_speed | constant_torque | motor_line | gear | shaft_segment, ...}");
  const std::string type =
      drive ? drive->choice("type", {"constant_speed", "constant_torque", "motor_line", "gear", "shaft_segment"})
            : "constant_speed";
  if (type == "constant_speed") {
    if (drive) drive->allow_only({"type", "speed"});
    const bool inner = drive && drive->has("speed");
    if (inner && p.has("speed")) drive->child("speed").fail("expected the speed once: here or at params.speed, not both");
    params.speed = inner ? drive->positive_quantity("speed", dim::angular_velocity)
                         : p.positive_quantity("speed", dim::angular_velocity);
    for (const char* key : {"inertia", "flywheel", "initial_speed"})
      if (p.has(key))
        p.child(key).fail(std::string("expected no ") + key +
                          " with a constant-speed drive (an ideal speed source ignores inertia): "
                          "set drive.type to constant_torque or motor_line");
    return;
  }
  if (type == "gear") {
    // Driven by another participant's shaft (a cvt) through a rigid, lossless gear
    // (docs/press-line.md): the speed comes from there, the inertia is carried there.
    drive->allow_only({"type", "ratio"});
    params.gear_ratio = drive->positive_quantity("ratio", dim::dimensionless);
    if (p.has("initial_speed"))
      p.child("initial_speed").fail("expected no initial_speed with a gear drive: the driving shaft sets the speed");
    params.speed = p.non_negative_quantity_or("speed", dim::angular_velocity, 0.0);  // nominal, for the analyses
  } else if (type == "shaft_segment") {
    // A station of a line shaft, driven by the upstream shaft (another cam_shaft's angle and
    // speed) through an elastic segment (docs/line-shaft.md).
    drive->allow_only({"type", "stiffness", "damping"});
    params.segment = cam::ShaftSegment{drive->positive_quantity("stiffness", dim::torsional_stiffness),
                                       drive->non_negative_quantity_or("damping", dim::rotational_damping, 0.0)};
  } else if (type == "constant_torque") {
    drive->allow_only({"type", "torque"});
    params.drive.type = cam::DriveType::constant_torque;
    params.drive.torque_nm = drive->quantity("torque", dim::torque);
  } else {
    drive->allow_only({"type", "stall_torque", "no_load_speed"});
    params.drive.type = cam::DriveType::motor_line;
    params.drive.stall_torque_nm = drive->positive_quantity("stall_torque", dim::torque);
    params.drive.no_load_speed_rad_s = drive->positive_quantity("no_load_speed", dim::angular_velocity);
  }
  if (type != "gear") {
    // Nominal speed: the design speed of the analyses and the default initial speed.
    params.speed = p.positive_quantity("speed", dim::angular_velocity);
    params.initial_speed = p.quantity_or("initial_speed", dim::angular_velocity, params.speed);
  }
  double inertia = p.non_negative_quantity_or("inertia", dim::inertia, 0.0);
  if (auto flywheel = p.optional_child("flywheel")) {
    if (!flywheel->is_map()) flywheel->fail("expected a map {inertia} or {radius, thickness, density}");
    flywheel->allow_only({"inertia", "radius", "thickness", "density"});
    if (flywheel->has("inertia")) {
      for (const char* key : {"radius", "thickness", "density"})
        if (flywheel->has(key)) flywheel->child(key).fail("expected either inertia or a disc {radius, thickness, density}, not both");
      inertia += flywheel->positive_quantity("inertia", dim::inertia);
    } else {
      // A solid steel disc unless told otherwise (the report's flywheel).
      inertia += cam::disc_inertia(flywheel->positive_quantity("radius", dim::length),
                                   flywheel->positive_quantity("thickness", dim::length),
                                   flywheel->positive_quantity_or("density", dim::density, 7800.0));
    }
  }
  if (!(inertia > 0.0) && type != "gear")
    p.fail("expected a shaft inertia > 0 for a torque or shaft-segment drive: give inertia (shaft, kg m^2) and/or a flywheel");
  params.inertia_kgm2 = inertia;
}

}  // namespace

cam::CamShaftParams parse_cam_shaft_params(const ConfigNode& p) {
  p.allow_only({"speed", "drive", "inertia", "flywheel", "initial_speed", "pitch_radius", "eccentricity",
                "initial_angle", "law"});
  // speed (0 here) and the drive come from parse_drive.
  cam::CamShaftParams params{parse_motion_law(p.child("law")), p.positive_quantity("pitch_radius", dim::length),
                             p.quantity_or("eccentricity", dim::length, 0.0), 0.0,
                             p.quantity_or("initial_angle", dim::angle, 0.0)};
  if (std::abs(params.eccentricity) >= params.pitch_radius)
    p.child("eccentricity").fail("expected |eccentricity| below the pitch radius");
  parse_drive(p, params);
  return params;
}

namespace {

std::unique_ptr<models::Block> make_cam_shaft(const ConfigNode& p, const ConfigNode*) {
  return std::make_unique<cam::CamShaftBlock>(parse_cam_shaft_params(p));
}

}  // namespace

NodeType cam_shaft_node_type() {
  return {"cam_shaft",
          "cam shaft: motion law and pressure angle, driven at constant speed, by a torque (constant, motor "
          "line) on its inertia and flywheel, or through a gear by a cvt; publishes CamState",
          transport::find_topic_type("CamState"),
          "state",
          make_cam_shaft,
          // The follower's torque without its reflected-inertia part, and that inertia: a
          // dynamic shaft carries m S'^2 itself (no algebraic loop); at constant speed
          // drive_torque_rest equals drive_torque.
          {{transport::find_topic_type("FollowerState"),
            {{"drive_torque_rest", "load_torque"}, {"reflected_inertia", "reflected_inertia"}}},
           // A gear drive: the driving shaft's speed and acceleration (docs/press-line.md).
           {transport::find_topic_type("CvtState"),
            {{"output_speed", "drive_speed"}, {"output_acceleration", "drive_acceleration"}}},
           // A line shaft (docs/line-shaft.md): from the upstream station its speed (drive:
           // shaft_segment), from the downstream station the torque its segment takes
           // (drive_load_torque). Which one a connection carries, its `fields:` says.
           {transport::find_topic_type("CamState"),
            {{"speed", "drive_speed"}, {"drive_load_torque", "downstream_torque"}}}}};
}

}  // namespace mechsim::cosim
