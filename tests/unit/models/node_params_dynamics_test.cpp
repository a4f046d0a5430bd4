// The scene keys of the dynamic cam models (docs/cam-dynamics.md): cam_shaft `drive`,
// `inertia`, `flywheel`, `initial_speed`, and the follower's `model: flexible` section.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "mechsim/config/config_node.h"
#include "mechsim/catalog/node_params.h"

namespace mechsim::cosim {
namespace {

constexpr double pi = std::numbers::pi;
const std::string kLaw = "law: [{type: full_cycloid, start: 0 deg, span: 180 deg, lift: 10 mm}, "
                         "{type: full_cycloid, start: 180 deg, span: 180 deg, lift: -10 mm}]\n"
                         "pitch_radius: 65 mm\n";

models::cam::CamShaftParams shaft(const std::string& yaml) {
  return parse_cam_shaft_params(config::ConfigNode::from_string(kLaw + yaml, "scene.yaml"));
}

FollowerConfig follower(const std::string& yaml) {
  return parse_follower_params(config::ConfigNode::from_string("mass: 25 kg\n" + yaml, "scene.yaml"));
}

// The key path a refusal names ("<root>" for the params map itself, "accepted" when
// nothing is refused).
template <typename F>
std::string refused_at(F&& parse) {
  try {
    parse();
  } catch (const config::ConfigError& e) {
    return e.key_path().empty() ? "<root>" : e.key_path();
  }
  return "accepted";
}

TEST(CamShaftParams, ConstantSpeedAtTheTopOrInTheDrive) {
  EXPECT_DOUBLE_EQ(shaft("speed: 30 rpm").speed, pi);
  const auto p = shaft("drive: {type: constant_speed, speed: 60 rpm}");
  EXPECT_DOUBLE_EQ(p.speed, 2 * pi);
  EXPECT_FALSE(p.drive.is_torque_source());
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ndrive: {type: constant_speed, speed: 30 rpm}"); }), "drive.speed");
  EXPECT_EQ(refused_at([] { shaft("drive: {type: constant_speed}"); }), "speed");
  // An ideal speed source ignores inertia: giving one is a mistake worth a message.
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\nflywheel: {inertia: 7 kg m^2}"); }), "flywheel");
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ninitial_speed: 0 rpm"); }), "initial_speed");
}

TEST(CamShaftParams, TorqueDrivesWithShaftAndFlywheelInertia) {
  const auto c = shaft("speed: 30 rpm\ndrive: {type: constant_torque, torque: 0.45833 N m}\n"
                       "inertia: 0.01 kg m^2\nflywheel: {inertia: 7.2 kg m^2}");
  EXPECT_EQ(c.drive.type, models::cam::DriveType::constant_torque);
  EXPECT_DOUBLE_EQ(c.drive.torque_nm, 0.45833);
  EXPECT_DOUBLE_EQ(c.inertia_kgm2, 7.21);          // shaft + flywheel
  EXPECT_DOUBLE_EQ(c.initial_speed.value(), pi);   // default: the nominal speed
  const auto m = shaft("speed: 30 rpm\ninitial_speed: 0 rpm\n"
                       "drive: {type: motor_line, stall_torque: 20 N m, no_load_speed: 31 rpm}\n"
                       "flywheel: {radius: 329.23 mm, thickness: 50 mm}");
  EXPECT_EQ(m.drive.type, models::cam::DriveType::motor_line);
  EXPECT_DOUBLE_EQ(m.drive.stall_torque_nm, 20.0);
  EXPECT_DOUBLE_EQ(m.drive.no_load_speed_rad_s, 31.0 * pi / 30.0);
  EXPECT_EQ(m.initial_speed.value(), 0.0);
  // A steel disc unless told otherwise: I = π ρ t R⁴/2.
  EXPECT_NEAR(m.inertia_kgm2, pi * 7800.0 * 0.05 * std::pow(0.32923, 4) / 2, 1e-12);
}

TEST(CamShaftParams, RefusesIncompleteOrContradictoryDrives) {
  // A torque drive needs an inertia to accelerate (dwells reflect no follower inertia).
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ndrive: {type: constant_torque, torque: 1 N m}"); }), "<root>");
  // The nominal speed stays required: the design analyses use it.
  EXPECT_EQ(refused_at([] { shaft("drive: {type: constant_torque, torque: 1 N m}\ninertia: 1 kg m^2"); }), "speed");
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ninertia: 1 kg m^2\ndrive: {type: constant_torque, stall_torque: 1 N m}"); }),
            "drive.stall_torque");  // a key of another drive type
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ninertia: 1 kg m^2\ndrive: {type: motor_line, stall_torque: 20 N m}"); }),
            "drive.no_load_speed");
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ninertia: 1 kg m^2\ndrive: {type: turbine}"); }), "drive.type");
  EXPECT_EQ(refused_at([] {
              shaft("speed: 30 rpm\ndrive: {type: constant_torque, torque: 1 N m}\n"
                    "flywheel: {inertia: 1 kg m^2, radius: 0.3 m}");
            }),
            "flywheel.radius");
  EXPECT_EQ(refused_at([] { shaft("speed: 30 rpm\ndrive: {type: constant_torque, torque: 1 N m}\ninertia: 1 kg"); }),
            "inertia");
}

TEST(FollowerParams, FlexibleModelAndItsDampers) {
  const auto contact = follower("model: flexible\nflexible: {stiffness: 574.19 N/mm, damping_ratio: 0.08}");
  EXPECT_EQ(contact.model, "flexible");
  EXPECT_DOUBLE_EQ(contact.contact.stiffness_n_per_m, 574190.0);
  const double c = 2 * 0.08 * std::sqrt(574190.0 * 25.0);  // c = 2ζ√(k_f m)
  EXPECT_DOUBLE_EQ(contact.contact.contact_damping_n_s_per_m, c);  // default: in the contact
  EXPECT_EQ(contact.contact.frame_damping_n_s_per_m, 0.0);
  const auto frame = follower("model: flexible\nflexible: {stiffness: 574.19 N/mm, damping_ratio: 0.08, damper: frame}");
  EXPECT_EQ(frame.contact.contact_damping_n_s_per_m, 0.0);
  EXPECT_DOUBLE_EQ(frame.contact.frame_damping_n_s_per_m, c);
  const auto both = follower("model: flexible\nflexible: {stiffness: 500 N/mm, contact_damping: 300 N s/m, "
                             "frame_damping: 20 N s/m, initial_lift: 5 mm}");
  EXPECT_DOUBLE_EQ(both.contact.contact_damping_n_s_per_m, 300.0);
  EXPECT_DOUBLE_EQ(both.contact.frame_damping_n_s_per_m, 20.0);
  EXPECT_DOUBLE_EQ(both.flexible().initial_lift_m, 0.005);
  EXPECT_EQ(follower("").model, "rigid");
}

TEST(FollowerParams, RefusesMisplacedFlexibleKeys) {
  EXPECT_EQ(refused_at([] { follower("model: flexible"); }), "flexible");
  EXPECT_EQ(refused_at([] { follower("flexible: {stiffness: 500 N/mm}"); }), "flexible");  // rigid by default
  EXPECT_EQ(refused_at([] { follower("model: flexible\nflexible: {damping_ratio: 0.08}"); }), "flexible.stiffness");
  EXPECT_EQ(refused_at([] {
              follower("model: flexible\nflexible: {stiffness: 500 N/mm, damping_ratio: 0.08, contact_damping: 1 N s/m}");
            }),
            "flexible.contact_damping");
  EXPECT_EQ(refused_at([] { follower("model: flexible\nflexible: {stiffness: 500 N/mm, damper: frame}"); }),
            "flexible.damper");
  EXPECT_EQ(refused_at([] { follower("model: flexible\nflexible: {stiffness: 500 N/mm, damping_ratio: 0.08, damper: guide}"); }),
            "flexible.damper");
  EXPECT_EQ(refused_at([] { follower("model: flexible\nflexible: {stiffness: 500 N/m/s}"); }), "flexible.stiffness");
}

}  // namespace
}  // namespace mechsim::cosim
