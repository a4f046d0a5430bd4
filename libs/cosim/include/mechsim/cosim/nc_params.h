// Parsing of the NC slide node types' `params:` (servo_amplifier, tachometer, slide) and of
// the motor-spindle coupling element of a connection, shared by the node catalog and the
// NC analyses (`mechsim motor-bode`, `mechsim slide-modes`). Every key is optional with the
// spec's value (nc_slide.md) as default; docs/scenes.md lists them.
#pragma once

#include "mechsim/config/config_node.h"
#include "mechsim/models/nc/coupling.h"
#include "mechsim/models/nc/motor_tacho.h"
#include "mechsim/models/nc/servo_amplifier_block.h"
#include "mechsim/models/nc/slide_block.h"

namespace mechsim::cosim {

models::nc::MotorTachoParams parse_motor_tacho_params(const config::ConfigNode& params);
// The slide data keys (slide_mass, spindle_diameter, lead, ...); other keys are left to the caller.
models::nc::SlideDriveData parse_slide_drive_data(const config::ConfigNode& params);
models::nc::SlideBlockOptions parse_slide_options(const config::ConfigNode& params);
models::nc::ServoAmplifierParams parse_servo_amplifier_params(const config::ConfigNode& params);

// The coupling element of a connection: {scheme: compliant | torque | interface_jacobian,
// stiffness, damping, levels}. compliant: both sides evaluate the spring-damper from their
// own state and the partner's reconstructed angle and speed; torque: the slide side
// evaluates it and sends the torque; interface_jacobian: both blocks take the torque as an
// input and solve `levels` torque levels per macro step from each other's predictions
// (libs/cosim/include/mechsim/cosim/coupling/interface_jacobian.h).
struct CouplingSpec {
  std::string scheme = "compliant";
  models::nc::CouplingParams params;
  int levels = 10;  // interface_jacobian: torque levels per macro step (1..16)
};
CouplingSpec parse_coupling(const config::ConfigNode& coupling);

}  // namespace mechsim::cosim
