// Node type `follower`: the translating roller follower, publishing <name>/state
// (FollowerState). Reads the cam shaft's CamState. `model: rigid` is the kinetostatic
// follower of spec cam.md §3; `model: flexible` the mass behind a follower stiffness with
// a unilateral contact (§5 model (b)), with lift-off and landing events.
#include <numbers>
#include <optional>
#include <string>

#include "mechsim/catalog/catalog.h"
#include "mechsim/catalog/node_params.h"
#include "mechsim/models/follower/flexible_follower_block.h"
#include "mechsim/models/follower/follower_block.h"

namespace mechsim::cosim {

namespace fol = models::follower;
using config::ConfigNode;
namespace dim = config::dim;

namespace {

// `flexible:` {stiffness, damping_ratio + damper | contact_damping / frame_damping,
// initial_lift}.
void parse_flexible(const ConfigNode& f, FollowerConfig& config) {
  if (!f.is_map()) f.fail("expected a map {stiffness, damping_ratio, damper, ...}");
  f.allow_only({"stiffness", "damping_ratio", "damper", "contact_damping", "frame_damping", "initial_lift"});
  fol::FollowerContact& c = config.contact;
  c.stiffness_n_per_m = f.positive_quantity("stiffness", dim::stiffness);
  if (f.has("damping_ratio")) {
    for (const char* key : {"contact_damping", "frame_damping"})
      if (f.has(key))
        f.child(key).fail("expected either damping_ratio (with damper) or contact_damping/frame_damping, not both");
    const double ratio = f.number("damping_ratio");
    if (!(ratio >= 0.0)) f.child("damping_ratio").fail("expected a damping ratio >= 0, e.g. 0.08");
    const double damping = fol::damping_for_ratio(ratio, c.stiffness_n_per_m, config.params.mass);
    // Where the ζ damper sits: in the contact (on Ṡ − ẏ, only the vibration dissipates) or
    // from the mass to the frame (on ẏ, the report's model (a) as printed).
    if (f.choice_or("damper", {"contact", "frame"}, "contact") == "contact")
      c.contact_damping_n_s_per_m = damping;
    else
      c.frame_damping_n_s_per_m = damping;
  } else {
    if (f.has("damper")) f.child("damper").fail("expected damper only together with damping_ratio");
    c.contact_damping_n_s_per_m = f.non_negative_quantity_or("contact_damping", dim::viscous_damping, 0.0);
    c.frame_damping_n_s_per_m = f.non_negative_quantity_or("frame_damping", dim::viscous_damping, 0.0);
  }
  config.initial_lift = f.quantity_or("initial_lift", dim::length, 0.0);
}

}  // namespace

FollowerConfig parse_follower_params(const ConfigNode& p) {
  p.allow_only({"model", "mass", "spring", "loads", "roller_radius", "flexible"});
  FollowerConfig config;
  config.model = p.choice_or("model", {"rigid", "flexible"}, "rigid");
  config.roller_radius = p.non_negative_quantity_or("roller_radius", dim::length, 0.0);
  fol::FollowerParams& params = config.params;
  params.mass = p.positive_quantity("mass", dim::mass);
  if (auto spring = p.optional_child("spring")) {
    spring->allow_only({"stiffness", "preload"});
    params.spring.stiffness_n_per_m = spring->non_negative_quantity("stiffness", dim::stiffness);
    params.spring.preload_n = spring->non_negative_quantity_or("preload", dim::force, 0.0);
  }
  if (auto loads = p.optional_child("loads")) {
    if (!loads->is_sequence()) loads->fail("expected a list of {from, to, force}");
    for (std::size_t i = 0; i < loads->size(); ++i) {
      ConfigNode l = loads->at(i);
      l.allow_only({"from", "to", "force", "end_force"});
      fol::FunctionalLoad load{l.quantity("from", dim::angle), l.quantity("to", dim::angle), l.quantity("force", dim::force)};
      if (l.has("end_force")) {  // linear in the cam angle from `force` at `from` to `end_force` at `to`
        load.ramp = true;
        load.end_force_n = l.quantity("end_force", dim::force);
      }
      if (!(load.end_rad > load.start_rad)) l.child("to").fail("expected an end angle after 'from'");
      // The loads act on half-open intervals of the cam angle that must not overlap.
      for (const auto& other : params.loads)
        if (load.start_rad < other.end_rad && other.start_rad < load.end_rad)
          l.fail("expected a load interval that overlaps no other; [" + std::to_string(load.start_rad * 180 / std::numbers::pi) +
                 ", " + std::to_string(load.end_rad * 180 / std::numbers::pi) + ") deg overlaps [" +
                 std::to_string(other.start_rad * 180 / std::numbers::pi) + ", " +
                 std::to_string(other.end_rad * 180 / std::numbers::pi) + ") deg");
      params.loads.push_back(load);
    }
  }
  const std::optional<ConfigNode> flexible = p.optional_child("flexible");
  if (config.model == "flexible") {
    parse_flexible(flexible ? *flexible : p.child("flexible"), config);  // child(): "missing key"
  } else if (flexible) {
    flexible->fail("expected no flexible: section with model: rigid (set model: flexible)");
  }
  return config;
}

namespace {

std::unique_ptr<models::Block> make_follower(const ConfigNode& p, const ConfigNode*) {
  const FollowerConfig config = parse_follower_params(p);
  if (config.model == "flexible") return std::make_unique<fol::FlexibleFollowerBlock>(config.flexible());
  return std::make_unique<fol::FollowerBlock>(config.params);
}

}  // namespace

NodeType follower_node_type() {
  return {"follower",
          "cam follower: rigid (kinetostatic) or flexible (follower stiffness, unilateral contact with lift-off "
          "and landing events) translating roller follower; publishes FollowerState",
          transport::find_topic_type("FollowerState"),
          "state",
          make_follower,
          {{transport::find_topic_type("CamState"),
            {{"angle", "angle"}, {"speed", "speed"}, {"acceleration", "acceleration"}, {"lift", "lift"},
             {"lift_d1", "lift_d1"}, {"lift_d2", "lift_d2"}, {"pressure_angle", "pressure_angle"}}}}};
}

}  // namespace mechsim::cosim
