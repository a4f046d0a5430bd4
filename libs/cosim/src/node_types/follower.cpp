// Node type `follower`: the translating roller follower (rigid, kinetostatic), publishing
// <name>/state (FollowerState). Reads the cam shaft's CamState.
#include "mechsim/cosim/catalog.h"
#include "mechsim/cosim/node_params.h"
#include "mechsim/models/follower/follower_block.h"

namespace mechsim::cosim {

namespace fol = models::follower;
using config::ConfigNode;
namespace dim = config::dim;

FollowerConfig parse_follower_params(const ConfigNode& p) {
  p.allow_only({"model", "mass", "spring", "loads", "roller_radius"});
  FollowerConfig config;
  config.model = p.choice_or("model", {"rigid"}, "rigid");
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
      l.allow_only({"from", "to", "force"});
      fol::FunctionalLoad load{l.quantity("from", dim::angle), l.quantity("to", dim::angle), l.quantity("force", dim::force)};
      if (!(load.end_rad > load.start_rad)) l.child("to").fail("expected an end angle after 'from'");
      params.loads.push_back(load);
    }
  }
  return config;
}

namespace {

std::unique_ptr<models::Block> make_follower(const ConfigNode& p) {
  return std::make_unique<fol::FollowerBlock>(parse_follower_params(p).params);
}

}  // namespace

NodeType follower_node_type() {
  return {"follower",
          "cam follower: rigid translating roller follower, kinetostatic contact force; publishes FollowerState",
          transport::find_topic_type("FollowerState"),
          "state",
          make_follower,
          {{transport::find_topic_type("CamState"),
            {{"angle", "angle"}, {"speed", "speed"}, {"lift", "lift"}, {"lift_d1", "lift_d1"},
             {"lift_d2", "lift_d2"}, {"pressure_angle", "pressure_angle"}}}}};
}

}  // namespace mechsim::cosim
