// Node type `tachometer`: the DC servo motor with its tachometer on a flexible shaft (spec
// nc_slide.md §1), publishing <name>/state (TachoState). Reads the armature voltage and,
// across the coupling, the spindle's angle and speed (compliant) or the coupling torque
// (torque; interface_jacobian, where the torque comes from the coupling solve).
#include "mechsim/catalog/catalog.h"
#include "mechsim/catalog/coupling/coupling_spec.h"
#include "mechsim/catalog/nc_params.h"
#include "mechsim/models/nc/motor_tacho_block.h"

namespace mechsim::cosim {

namespace {
std::unique_ptr<models::Block> make_tachometer(const config::ConfigNode& p, const config::ConfigNode* coupling) {
  models::nc::MotorTachoBlockOptions options;
  options.motor = parse_motor_tacho_params(p);
  if (coupling) {
    const coupling::CouplingSpec spec = coupling::parse_coupling(*coupling);
    options.coupling = spec.params;
    options.coupling_input = spec.scheme == coupling::CouplingScheme::compliant ? models::nc::CouplingInput::compliant
                                                                              : models::nc::CouplingInput::torque;
  }
  return std::make_unique<models::nc::MotorTachoBlock>(options);
}
}  // namespace

NodeType tachometer_node_type() {
  return {"tachometer",
          "DC servo motor with tachometer on a flexible shaft (4 states + motor angle); publishes TachoState",
          transport::find_topic_type("TachoState"),
          "state",
          make_tachometer,
          {{transport::find_topic_type("ServoCommand"), {{"armature_voltage", "armature_voltage"}}},
           {transport::find_topic_type("SlideState"),
            {{"coupling_torque", "load_torque"}, {"spindle_angle", "spindle_angle"}, {"spindle_speed", "spindle_speed"}}}},
          // The coupling torque loads the rotor: the motor's angle counts positively in the twist.
          CutPort{"load_torque", "motor_angle", "motor_speed", +1}};
}

}  // namespace mechsim::cosim
