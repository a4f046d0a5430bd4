#include "mechsim/transport/topic_types.h"

#include <stdexcept>

namespace mechsim::transport {

int TopicType::field_index(std::string_view name) const {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name == name) return static_cast<int>(i);
  return -1;
}

bool TopicType::same_as(const TopicType& other) const {
  if (this == &other) return true;
  if (idl_name != other.idl_name || layout != other.layout || fields.size() != other.fields.size()) return false;
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name != other.fields[i].name || fields[i].kind != other.fields[i].kind) return false;
  return true;
}

TopicType fmu_topic_type(std::vector<FieldInfo> fields) {
  TopicType t{kFmuOutputsTypeName, "fmu.idl", std::move(fields), TopicLayout::sequences};
  for (FieldKind kind : {FieldKind::f64, FieldKind::i32, FieldKind::boolean}) {
    std::size_t n = 0;
    for (const auto& f : t.fields) n += f.kind == kind ? 1 : 0;
    if (n > kFmuOutputsBound)
      throw std::invalid_argument("FmuOutputs carries at most " + std::to_string(kFmuOutputsBound) +
                                  " values of one type, got " + std::to_string(n));
  }
  return t;
}

std::vector<std::size_t> sequence_positions(const TopicType& type) {
  std::size_t reals = 0, integers = 0, booleans = 0;
  std::vector<std::size_t> at;
  for (const auto& f : type.fields)
    at.push_back(f.kind == FieldKind::f64 ? reals++ : f.kind == FieldKind::i32 ? integers++ : booleans++);
  return at;
}

namespace {
FieldInfo f64(const char* name) { return {name, FieldKind::f64}; }
// A field with physical bounds: far beyond what any mechanism mechsim models can produce
// (an amplifier of 1 kV, a motor at 10 000 rad/s), never a design limit of one scene.
FieldInfo bounded(const char* name, double min, double max, const char* unit) { return {name, FieldKind::f64, min, max, unit}; }
FieldInfo flag(const char* name) { return {name, FieldKind::boolean}; }
// A field with a unit but no physical bounds (finite only).
FieldInfo unbounded(const char* name, const char* unit) {
  return {name, FieldKind::f64, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), unit};
}

// Mirrors idl/cam.idl.
const TopicType kCamState{"mechsim::msg::CamState", "cam.idl",
                          {f64("angle"), bounded("speed", -1e4, 1e4, "rad/s"), f64("acceleration"), f64("lift"), f64("lift_d1"),
                           f64("lift_d2"), f64("pressure_angle"), f64("shaft_torque"), f64("drive_power"),
                           f64("drive_load_torque"), f64("drive_load_inertia")}};
// Mirrors idl/follower.idl.
const TopicType kFollowerState{"mechsim::msg::FollowerState", "follower.idl",
                               {f64("position"), f64("velocity"), f64("acceleration"),
                                f64("contact_force"), flag("contact"), f64("lift_off_count"),
                                f64("drive_torque"), f64("drive_torque_rest"), f64("reflected_inertia"),
                                f64("spring_force"), f64("load_force"), f64("inertia_force")}};
// Mirrors idl/servo.idl.
const TopicType kServoCommand{"mechsim::msg::ServoCommand", "servo.idl",
                              {bounded("armature_voltage", -1e3, 1e3, "V"), f64("position_reference"), f64("following_error"),
                               f64("velocity_error"), flag("saturated")}};
// Mirrors idl/tacho.idl.
const TopicType kTachoState{"mechsim::msg::TachoState", "tacho.idl",
                            {f64("tacho_voltage"), f64("motor_angle"), bounded("motor_speed", -1e4, 1e4, "rad/s"),
                             bounded("armature_current", -1e4, 1e4, "A"),
                             f64("coupling_torque")}};
// Mirrors idl/slide.idl.
const TopicType kSlideState{"mechsim::msg::SlideState", "slide.idl",
                            {f64("spindle_angle"), f64("spindle_speed"), f64("slide_position"), f64("slide_speed"),
                             f64("coupling_torque")}};
// Mirrors idl/scale.idl.
const TopicType kScaleReading{"mechsim::msg::ScaleReading", "scale.idl", {f64("measured_position"), f64("measurement_error")}};
// Mirrors idl/cvt.idl.
const TopicType kCvtState{"mechsim::msg::CvtState", "cvt.idl",
                          {f64("input_speed"), f64("output_speed"), f64("output_acceleration"), f64("ratio"), f64("ratio_setting"), f64("ratio_command"), f64("motor_torque"), f64("belt_torque"), f64("input_torque"), f64("output_torque"), f64("eta_PB"), f64("eta_SYS"), bounded("clamping_force", 0.0, 1e7, "N"), f64("slip_margin"), f64("sigma_1"), f64("sigma_2"), f64("sigma_3"), f64("sigma_4"), f64("belt_loss"), f64("bearing_loss"), f64("flags"),
                           flag("gross_slip"), flag("torque_reversal"), flag("outside_model")}};
// Mirrors idl/coupling.idl (up to 16 torque levels per macro step).
TopicType coupling_prediction_type() {
  TopicType t{"mechsim::msg::CouplingPrediction", "coupling.idl", {f64("angle"), f64("assumed_torque"), f64("levels")}};
  for (const char* prefix : {"predicted_angle_", "sensitivity_"})
    for (int j = 1; j <= 16; ++j) t.fields.push_back({prefix + std::to_string(j), FieldKind::f64});
  return t;
}
const TopicType kCouplingPrediction = coupling_prediction_type();
// Mirrors idl/step.idl.
const TopicType kStepProposal{"mechsim::msg::StepProposal", "step.idl",
                              {bounded("step_length", 0.0, std::numeric_limits<double>::infinity(), "s"), flag("event"),
                               unbounded("event_time", "s"),
                               bounded("error_estimate", 0.0, std::numeric_limits<double>::infinity(), "1"),
                               unbounded("state_event_time", "s")}};
}  // namespace

const std::vector<const TopicType*>& all_topic_types() {
  static const std::vector<const TopicType*> types{&kCamState, &kFollowerState, &kServoCommand, &kTachoState,
                                                          &kSlideState, &kCouplingPrediction, &kCvtState, &kStepProposal,
                                                          &kScaleReading};
  return types;
}

const TopicType* find_topic_type(std::string_view name) {
  for (const TopicType* t : all_topic_types()) {
    std::string_view scoped = t->idl_name;
    std::string_view short_name = scoped.substr(scoped.rfind(':') + 1);
    if (name == scoped || name == short_name) return t;
  }
  return nullptr;
}

void as_on_the_wire(const TopicType& type, std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size() && i < type.fields.size(); ++i)
    if (type.fields[i].kind == FieldKind::boolean) values[i] = values[i] != 0.0 ? 1.0 : 0.0;
    else if (type.fields[i].kind == FieldKind::i32) values[i] = static_cast<std::int32_t>(values[i]);
}

}  // namespace mechsim::transport
