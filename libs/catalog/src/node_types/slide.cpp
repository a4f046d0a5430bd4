// Node type `slide`: spindle, nut and slide behind the motor coupling (spec nc_slide.md
// §2-§3), rigid, two-mass or modal, publishing <name>/state (SlideState). Reads the motor's
// angle and speed across the coupling and evaluates it itself, or (interface_jacobian) takes
// the coupling torque from the coupling solve.
#include "mechsim/catalog/catalog.h"
#include "mechsim/catalog/coupling/coupling_spec.h"
#include "mechsim/catalog/nc_params.h"
#include "mechsim/models/nc/slide_block.h"

namespace mechsim::cosim {

namespace {
std::unique_ptr<models::Block> make_slide(const config::ConfigNode& p, const config::ConfigNode* coupling) {
  models::nc::SlideBlockOptions options = parse_slide_options(p);
  if (coupling) {
    const coupling::CouplingSpec spec = coupling::parse_coupling(*coupling);
    options.coupling = spec.params;
    // compliant and torque: the slide side evaluates the element; interface_jacobian: the
    // torque comes from the coupling solve.
    options.coupling_input = spec.scheme == coupling::CouplingScheme::interface_jacobian ? models::nc::CouplingInput::torque
                                                                                         : models::nc::CouplingInput::compliant;
  }
  try {
    return std::make_unique<models::nc::SlideBlock>(options);
  } catch (const std::invalid_argument& e) {
    p.fail(std::string("expected consistent slide parameters: ") + e.what());
  }
}
}  // namespace

NodeType slide_node_type() {
  return {"slide",
          "ball-screw spindle, nut and slide (rigid, two-mass or modal) behind the coupling; publishes SlideState",
          transport::find_topic_type("SlideState"),
          "state",
          make_slide,
          {{transport::find_topic_type("TachoState"), {{"motor_angle", "motor_angle"}, {"motor_speed", "motor_speed"}}}},
          // The coupling torque drives the spindle: its angle counts negatively in the twist.
          CutPort{"drive_torque", "spindle_angle", "spindle_speed", -1}};
}

}  // namespace mechsim::cosim
