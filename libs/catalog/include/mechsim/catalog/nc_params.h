// Parsing of the NC slide node types' `params:` (servo_amplifier, tachometer, slide), shared
// by the node catalog and the NC analyses (`mechsim motor-bode`, `mechsim slide-modes`). Every key is optional with the
// spec's value (nc_slide.md) as default; docs/scenes.md lists them.
#pragma once

#include "mechsim/config/config_node.h"
#include "mechsim/models/nc/motor_tacho.h"
#include "mechsim/models/nc/servo_amplifier_block.h"
#include "mechsim/models/nc/slide_block.h"

namespace mechsim::cosim {

models::nc::MotorTachoParams parse_motor_tacho_params(const config::ConfigNode& params);
// The slide data keys (slide_mass, spindle_diameter, lead, ...); other keys are left to the caller.
models::nc::SlideDriveData parse_slide_drive_data(const config::ConfigNode& params);
models::nc::SlideBlockOptions parse_slide_options(const config::ConfigNode& params);
models::nc::ServoAmplifierParams parse_servo_amplifier_params(const config::ConfigNode& params);

// The coupling element of a connection (its scheme, stiffness, damping): coupling/coupling_spec.h.

}  // namespace mechsim::cosim
