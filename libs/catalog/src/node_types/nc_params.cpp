#include "mechsim/catalog/nc_params.h"

namespace mechsim::cosim {

using config::ConfigNode;
namespace dim = config::dim;
namespace nc = models::nc;

namespace {
const std::vector<std::string> kMotorKeys{"armature_resistance", "armature_inductance", "torque_constant",
                                          "tacho_constant", "rotor_inertia", "tacho_inertia", "shaft_stiffness",
                                          "rotor_damping", "tacho_damping", "shaft_damping", "load_inertia"};
const std::vector<std::string> kSlideDataKeys{"slide_mass", "spindle_diameter", "lead", "spindle_length", "density",
                                              "shear_modulus", "coupling_inertia", "coupling_stiffness", "slide_inertia"};
}  // namespace

nc::MotorTachoParams parse_motor_tacho_params(const ConfigNode& p) {
  p.allow_only(kMotorKeys);
  nc::MotorTachoParams m;
  m.armature_resistance = p.positive_quantity_or("armature_resistance", dim::resistance, m.armature_resistance);
  m.armature_inductance = p.positive_quantity_or("armature_inductance", dim::inductance, m.armature_inductance);
  m.torque_constant = p.positive_quantity_or("torque_constant", dim::torque_constant, m.torque_constant);
  m.tacho_constant = p.positive_quantity_or("tacho_constant", dim::tacho_constant, m.tacho_constant);
  m.motor_inertia = p.positive_quantity_or("rotor_inertia", dim::inertia, m.motor_inertia);
  m.tacho_inertia = p.positive_quantity_or("tacho_inertia", dim::inertia, m.tacho_inertia);
  m.shaft_stiffness = p.positive_quantity_or("shaft_stiffness", dim::torsional_stiffness, m.shaft_stiffness);
  m.motor_damping = p.non_negative_quantity_or("rotor_damping", dim::rotational_damping, m.motor_damping);
  m.tacho_damping = p.non_negative_quantity_or("tacho_damping", dim::rotational_damping, m.tacho_damping);
  m.shaft_damping = p.non_negative_quantity_or("shaft_damping", dim::rotational_damping, m.shaft_damping);
  const double load = p.non_negative_quantity_or("load_inertia", dim::inertia, 0.0);
  return load > 0 ? nc::with_load_inertia(m, load) : m;
}

nc::SlideDriveData parse_slide_drive_data(const ConfigNode& p) {
  nc::SlideDriveData d;
  d.slide_mass = p.positive_quantity_or("slide_mass", dim::mass, d.slide_mass);
  d.spindle_diameter = p.positive_quantity_or("spindle_diameter", dim::length, d.spindle_diameter);
  d.lead = p.positive_quantity_or("lead", dim::length, d.lead);
  d.spindle_length = p.positive_quantity_or("spindle_length", dim::length, d.spindle_length);
  d.density = p.positive_quantity_or("density", dim::density, d.density);
  d.shear_modulus = p.positive_quantity_or("shear_modulus", dim::pressure, d.shear_modulus);
  d.coupling_inertia = p.positive_quantity_or("coupling_inertia", dim::inertia, d.coupling_inertia);
  d.coupling_stiffness = p.positive_quantity_or("coupling_stiffness", dim::torsional_stiffness, d.coupling_stiffness);
  if (p.has("slide_inertia")) d.slide_inertia_override = p.positive_quantity("slide_inertia", dim::inertia);
  return d;
}

nc::SlideBlockOptions parse_slide_options(const ConfigNode& p) {
  std::vector<std::string> keys = kSlideDataKeys;
  keys.insert(keys.end(), {"variant", "modes", "nut_position", "spindle_damping", "guide_friction",
                           "coulomb_friction", "coulomb_velocity_scale"});
  p.allow_only(keys);
  nc::SlideBlockOptions o;
  o.drive = parse_slide_drive_data(p);
  const std::string variant = p.choice_or("variant", {"rigid", "two_mass", "modal"}, "two_mass");
  o.variant = variant == "rigid" ? nc::SlideVariant::rigid
              : variant == "modal" ? nc::SlideVariant::modal
                                   : nc::SlideVariant::two_mass;
  o.modal_shapes = static_cast<int>(p.integer_or("modes", o.modal_shapes));
  if (o.modal_shapes < 1 || o.modal_shapes > 40) p.child("modes").fail("expected a number of modes in 1..40");
  if (p.has("nut_position")) {
    o.nut_position = p.non_negative_quantity("nut_position", dim::length);
    if (*o.nut_position > o.drive.spindle_length)
      p.child("nut_position").fail("expected a position along the spindle (at most its length)");
  }
  o.spindle_damping = p.non_negative_quantity_or("spindle_damping", dim::rotational_damping, o.spindle_damping);
  o.guide_viscous_friction = p.non_negative_quantity_or("guide_friction", dim::viscous_damping, o.guide_viscous_friction);
  o.guide_coulomb_friction = p.non_negative_quantity_or("coulomb_friction", dim::force, o.guide_coulomb_friction);
  o.coulomb_velocity_scale = p.positive_quantity_or("coulomb_velocity_scale", dim::velocity, o.coulomb_velocity_scale);
  return o;
}

nc::ServoAmplifierParams parse_servo_amplifier_params(const ConfigNode& p) {
  p.allow_only({"position_gain", "velocity_gain", "integral_time", "antiwindup_time", "tacho_filter_time",
                "voltage_limit", "tacho_constant", "lead", "velocity_feedforward", "sample_time", "current_limit",
                "setpoint", "position_measurement"});
  nc::ServoAmplifierParams a;
  a.measure_on_motor = p.choice_or("position_measurement", {"spindle", "motor"}, "spindle") == "motor";
  a.position_gain = p.positive_quantity_or("position_gain", dim::frequency, a.position_gain);
  a.velocity_gain = p.positive_quantity_or("velocity_gain", dim::dimensionless, a.velocity_gain);
  a.integral_time = p.positive_quantity_or("integral_time", dim::time, a.integral_time);
  a.antiwindup_time = p.positive_quantity_or("antiwindup_time", dim::time, a.antiwindup_time);
  a.tacho_filter_time = p.positive_quantity_or("tacho_filter_time", dim::time, a.tacho_filter_time);
  a.voltage_limit = p.positive_quantity_or("voltage_limit", dim::voltage, a.voltage_limit);
  a.tacho_constant = p.positive_quantity_or("tacho_constant", dim::tacho_constant, a.tacho_constant);
  a.lead = p.positive_quantity_or("lead", dim::length, a.lead);
  a.velocity_feedforward = p.non_negative_quantity_or("velocity_feedforward", dim::dimensionless, a.velocity_feedforward);
  a.sample_time = p.non_negative_quantity_or("sample_time", dim::time, 0.0);
  if (auto cl = p.optional_child("current_limit")) {
    cl->allow_only({"max_current", "armature_resistance", "back_emf_per_tacho_volt"});
    a.current_limit.enabled = true;
    a.current_limit.max_current = cl->positive_quantity("max_current", dim::current);
    a.current_limit.armature_resistance =
        cl->positive_quantity_or("armature_resistance", dim::resistance, a.current_limit.armature_resistance);
    a.current_limit.back_emf_per_tacho_volt =
        cl->positive_quantity_or("back_emf_per_tacho_volt", dim::dimensionless, a.current_limit.back_emf_per_tacho_volt);
  }
  const ConfigNode s = p.child("setpoint");
  s.allow_only({"type", "start", "distance", "velocity", "acceleration"});
  const std::string type = s.choice("type", {"step", "ramp", "trapezoid", "external"});
  if (type == "external") {
    a.setpoint_source = nc::SetpointSource::external;
  } else {
    a.setpoint.kind = type == "step" ? nc::SetpointKind::step
                      : type == "ramp" ? nc::SetpointKind::ramp
                                       : nc::SetpointKind::trapezoid;
    a.setpoint.start_time = s.non_negative_quantity_or("start", dim::time, 0.0);
    a.setpoint.distance = s.quantity("distance", dim::length);
    if (type != "step") a.setpoint.velocity = s.positive_quantity("velocity", dim::velocity);
    if (type == "trapezoid") a.setpoint.acceleration = s.positive_quantity("acceleration", dim::acceleration);
  }
  return a;
}

}  // namespace mechsim::cosim
