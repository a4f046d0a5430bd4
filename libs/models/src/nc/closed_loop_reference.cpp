#include "mechsim/models/nc/closed_loop_reference.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace mechsim::models::nc {

namespace {
int require_port(int index, const char* what) {
  if (index < 0) throw std::logic_error(std::string("closed loop: sub-block lacks port ") + what);
  return index;
}
}  // namespace

SlideBlockOptions ClosedLoopReference::torque_coupled(SlideBlockOptions slide) {
  slide.coupling_input = CouplingInput::torque;
  return slide;
}

ClosedLoopReference::ClosedLoopReference(ClosedLoopOptions options)
    : Block("nc_closed_loop"),
      coupling_(options.coupling),
      amplifier_(options.amplifier),
      motor_(MotorTachoBlockOptions{options.motor, CouplingInput::torque, options.coupling}),
      slide_(torque_coupled(options.slide)) {
  p_.amp_tacho = require_port(amplifier_.input_index("tacho_voltage"), "tacho_voltage");
  p_.amp_angle = require_port(amplifier_.input_index("spindle_angle"), "spindle_angle");
  p_.amp_setpoint = amplifier_.input_index("position_setpoint");
  p_.amp_voltage = require_port(amplifier_.output_index("armature_voltage"), "armature_voltage");
  p_.amp_reference = require_port(amplifier_.output_index("position_reference"), "position_reference");
  p_.amp_error = require_port(amplifier_.output_index("velocity_error"), "velocity_error");
  p_.amp_saturated = require_port(amplifier_.output_index("saturated"), "saturated");
  p_.motor_voltage = require_port(motor_.input_index("armature_voltage"), "armature_voltage");
  p_.motor_load = require_port(motor_.input_index("load_torque"), "load_torque");
  p_.motor_tacho = require_port(motor_.output_index("tacho_voltage"), "tacho_voltage");
  p_.motor_angle = require_port(motor_.output_index("motor_angle"), "motor_angle");
  p_.motor_speed = require_port(motor_.output_index("motor_speed"), "motor_speed");
  p_.motor_current = require_port(motor_.output_index("armature_current"), "armature_current");
  p_.slide_torque = require_port(slide_.input_index("drive_torque"), "drive_torque");
  p_.slide_angle = require_port(slide_.output_index("spindle_angle"), "spindle_angle");
  p_.slide_speed = require_port(slide_.output_index("spindle_speed"), "spindle_speed");
  p_.slide_position = require_port(slide_.output_index("slide_position"), "slide_position");
  p_.slide_velocity = require_port(slide_.output_index("slide_speed"), "slide_speed");
  p_.slide_coupling = require_port(slide_.output_index("coupling_torque"), "coupling_torque");

  if (p_.amp_setpoint >= 0) in_setpoint_ = declare_required_input("position_setpoint", "m");
  // The setpoint reaches these through the (continuous) amplifier; position and speed do not.
  std::vector<int> ft;
  if (in_setpoint_ >= 0 && amplifier_.sample_time() == 0) ft.push_back(in_setpoint_);
  out_.slide_position = declare_output("slide_position", "m");
  out_.slide_speed = declare_output("slide_speed", "m/s");
  out_.spindle_angle = declare_output("spindle_angle", "rad");
  out_.motor_speed = declare_output("motor_speed", "rad/s");
  out_.armature_current = declare_output("armature_current", "A");
  out_.armature_voltage = declare_output("armature_voltage", "V", ft);
  out_.tacho_voltage = declare_output("tacho_voltage", "V");
  out_.coupling_torque = declare_output("coupling_torque", "N m");
  out_.position_reference = declare_output("position_reference", "m", ft);
  out_.velocity_error = declare_output("velocity_error", "V", ft);
  out_.saturated = declare_output("saturated", "1", ft);

  for (const Block* part : {static_cast<const Block*>(&amplifier_), static_cast<const Block*>(&motor_),
                            static_cast<const Block*>(&slide_)})
    for (std::size_t i = 0; i < part->state_names().size(); ++i)
      declare_state(part->type_name() + "." + part->state_names()[i], "");
}

void ClosedLoopReference::initial_state(double t0, std::span<double> x) const {
  amplifier_.initial_state(t0, x.subspan(amplifier_offset(), amplifier_.num_states()));
  motor_.initial_state(t0, x.subspan(motor_offset(), motor_.num_states()));
  slide_.initial_state(t0, x.subspan(slide_offset(), slide_.num_states()));
}

void ClosedLoopReference::evaluate(double t, std::span<const double> x, std::span<const double> u,
                                   Signals& s) const {
  const auto xa = part(x, amplifier_offset(), amplifier_), xm = part(x, motor_offset(), motor_);
  const auto xs = part(x, slide_offset(), slide_);
  // Motor and slide outputs that the loop needs come from their states alone (no
  // feedthrough); evaluate them with placeholder inputs, then close the loop.
  std::fill(std::begin(s.motor_in), std::end(s.motor_in), 0.0);
  std::fill(std::begin(s.slide_in), std::end(s.slide_in), 0.0);
  motor_.calc_outputs(t, xm, s.motor_in, s.motor_out);
  slide_.calc_outputs(t, xs, s.slide_in, s.slide_out);
  const double torque = coupling_torque(coupling_, s.motor_out[p_.motor_angle], s.motor_out[p_.motor_speed],
                                        s.slide_out[p_.slide_angle], s.slide_out[p_.slide_speed]);
  s.amplifier_in[p_.amp_tacho] = s.motor_out[p_.motor_tacho];
  s.amplifier_in[p_.amp_angle] = s.slide_out[p_.slide_angle];
  if (p_.amp_setpoint >= 0) s.amplifier_in[p_.amp_setpoint] = u[in_setpoint_];
  amplifier_.calc_outputs(t, xa, std::span(s.amplifier_in, amplifier_.num_inputs()), s.amplifier_out);
  s.motor_in[p_.motor_voltage] = s.amplifier_out[p_.amp_voltage];
  s.motor_in[p_.motor_load] = torque;
  s.slide_in[p_.slide_torque] = torque;
  slide_.calc_outputs(t, xs, s.slide_in, s.slide_out);  // now with the coupling torque
}

void ClosedLoopReference::derivatives(double t, std::span<const double> x, std::span<const double> u,
                                      std::span<double> dxdt) const {
  Signals s;
  evaluate(t, x, u, s);
  amplifier_.derivatives(t, part(x, amplifier_offset(), amplifier_),
                         std::span(s.amplifier_in, amplifier_.num_inputs()),
                         dxdt.subspan(amplifier_offset(), amplifier_.num_states()));
  motor_.derivatives(t, part(x, motor_offset(), motor_), s.motor_in,
                     dxdt.subspan(motor_offset(), motor_.num_states()));
  slide_.derivatives(t, part(x, slide_offset(), slide_), s.slide_in,
                     dxdt.subspan(slide_offset(), slide_.num_states()));
}

void ClosedLoopReference::calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                                       std::span<double> y) const {
  Signals s;
  evaluate(t, x, u, s);
  y[out_.slide_position] = s.slide_out[p_.slide_position];
  y[out_.slide_speed] = s.slide_out[p_.slide_velocity];
  y[out_.spindle_angle] = s.slide_out[p_.slide_angle];
  y[out_.motor_speed] = s.motor_out[p_.motor_speed];
  y[out_.armature_current] = s.motor_out[p_.motor_current];
  y[out_.armature_voltage] = s.amplifier_out[p_.amp_voltage];
  y[out_.tacho_voltage] = s.motor_out[p_.motor_tacho];
  y[out_.coupling_torque] = s.slide_out[p_.slide_coupling];
  y[out_.position_reference] = s.amplifier_out[p_.amp_reference];
  y[out_.velocity_error] = s.amplifier_out[p_.amp_error];
  y[out_.saturated] = s.amplifier_out[p_.amp_saturated];
}

void ClosedLoopReference::discrete_update(double t, std::span<double> x, std::span<const double> u) {
  Signals s;
  evaluate(t, x, u, s);
  amplifier_.discrete_update(t, x.subspan(amplifier_offset(), amplifier_.num_states()),
                             std::span<const double>(s.amplifier_in, amplifier_.num_inputs()));
}

}  // namespace mechsim::models::nc
