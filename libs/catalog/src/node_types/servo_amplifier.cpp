// Node type `servo_amplifier`: the NC position and velocity loop (spec nc_slide.md §3),
// publishing <name>/command (ServoCommand). Reads the tacho voltage and the spindle angle.
#include "mechsim/catalog/catalog.h"
#include "mechsim/catalog/nc_params.h"

namespace mechsim::cosim {

namespace {
std::unique_ptr<models::Block> make_servo_amplifier(const config::ConfigNode& p, const config::ConfigNode*) {
  models::nc::ServoAmplifierParams params = parse_servo_amplifier_params(p);
  try {
    return std::make_unique<models::nc::ServoAmplifierBlock>(params);
  } catch (const std::invalid_argument& e) {
    p.fail(std::string("expected consistent amplifier parameters: ") + e.what());
  }
}
}  // namespace

NodeType servo_amplifier_node_type() {
  return {"servo_amplifier",
          "NC servo amplifier: position loop, PI velocity loop, voltage and current limits; publishes ServoCommand",
          transport::find_topic_type("ServoCommand"),
          "command",
          make_servo_amplifier,
          {{transport::find_topic_type("TachoState"), {{"tacho_voltage", "tacho_voltage"}, {"motor_angle", "motor_angle"}}},
           {transport::find_topic_type("SlideState"), {{"spindle_angle", "spindle_angle"}}}}};
}

}  // namespace mechsim::cosim
