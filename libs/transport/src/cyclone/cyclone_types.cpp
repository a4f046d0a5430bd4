#include "cyclone_types.h"

#include <stdexcept>

#include "cam.h"
#include "coupling.h"
#include "cvt.h"
#include "follower.h"
#include "scale.h"
#include "servo.h"
#include "slide.h"
#include "step.h"
#include "tacho.h"

namespace mechsim::transport::cyclone {

namespace {
#define MECHSIM_F64(Struct, field) FieldSlot{offsetof(Struct, field), FieldKind::f64}
#define MECHSIM_FLAG(Struct, field) FieldSlot{offsetof(Struct, field), FieldKind::boolean}

std::vector<CycloneType> make_bindings() {
  std::vector<CycloneType> b;
  b.push_back({find_topic_type("CamState"), &mechsim_msg_CamState_desc, sizeof(mechsim_msg_CamState),
               {MECHSIM_F64(mechsim_msg_CamState, angle), MECHSIM_F64(mechsim_msg_CamState, speed),
                MECHSIM_F64(mechsim_msg_CamState, acceleration), MECHSIM_F64(mechsim_msg_CamState, lift),
                MECHSIM_F64(mechsim_msg_CamState, lift_d1),
                MECHSIM_F64(mechsim_msg_CamState, lift_d2),
                MECHSIM_F64(mechsim_msg_CamState, pressure_angle),
                MECHSIM_F64(mechsim_msg_CamState, shaft_torque),
                MECHSIM_F64(mechsim_msg_CamState, drive_power),
                MECHSIM_F64(mechsim_msg_CamState, drive_load_torque),
                MECHSIM_F64(mechsim_msg_CamState, drive_load_inertia)}});
  b.push_back({find_topic_type("FollowerState"), &mechsim_msg_FollowerState_desc,
               sizeof(mechsim_msg_FollowerState),
               {MECHSIM_F64(mechsim_msg_FollowerState, position),
                MECHSIM_F64(mechsim_msg_FollowerState, velocity),
                MECHSIM_F64(mechsim_msg_FollowerState, acceleration),
                MECHSIM_F64(mechsim_msg_FollowerState, contact_force),
                MECHSIM_FLAG(mechsim_msg_FollowerState, contact),
                MECHSIM_F64(mechsim_msg_FollowerState, lift_off_count),
                MECHSIM_F64(mechsim_msg_FollowerState, drive_torque),
                MECHSIM_F64(mechsim_msg_FollowerState, drive_torque_rest),
                MECHSIM_F64(mechsim_msg_FollowerState, reflected_inertia),
                MECHSIM_F64(mechsim_msg_FollowerState, spring_force),
                MECHSIM_F64(mechsim_msg_FollowerState, load_force),
                MECHSIM_F64(mechsim_msg_FollowerState, inertia_force)}});
  b.push_back({find_topic_type("ServoCommand"), &mechsim_msg_ServoCommand_desc, sizeof(mechsim_msg_ServoCommand),
               {MECHSIM_F64(mechsim_msg_ServoCommand, armature_voltage),
                MECHSIM_F64(mechsim_msg_ServoCommand, position_reference),
                MECHSIM_F64(mechsim_msg_ServoCommand, following_error),
                MECHSIM_F64(mechsim_msg_ServoCommand, velocity_error),
                MECHSIM_FLAG(mechsim_msg_ServoCommand, saturated)}});
  b.push_back({find_topic_type("TachoState"), &mechsim_msg_TachoState_desc, sizeof(mechsim_msg_TachoState),
               {MECHSIM_F64(mechsim_msg_TachoState, tacho_voltage), MECHSIM_F64(mechsim_msg_TachoState, motor_angle),
                MECHSIM_F64(mechsim_msg_TachoState, motor_speed), MECHSIM_F64(mechsim_msg_TachoState, armature_current),
                MECHSIM_F64(mechsim_msg_TachoState, coupling_torque)}});
  b.push_back({find_topic_type("SlideState"), &mechsim_msg_SlideState_desc, sizeof(mechsim_msg_SlideState),
               {MECHSIM_F64(mechsim_msg_SlideState, spindle_angle), MECHSIM_F64(mechsim_msg_SlideState, spindle_speed),
                MECHSIM_F64(mechsim_msg_SlideState, slide_position), MECHSIM_F64(mechsim_msg_SlideState, slide_speed),
                MECHSIM_F64(mechsim_msg_SlideState, coupling_torque)}});
  b.push_back({find_topic_type("ScaleReading"), &mechsim_msg_ScaleReading_desc, sizeof(mechsim_msg_ScaleReading),
               {MECHSIM_F64(mechsim_msg_ScaleReading, measured_position), MECHSIM_F64(mechsim_msg_ScaleReading, measurement_error)}});
  b.push_back({find_topic_type("CvtState"), &mechsim_msg_CvtState_desc, sizeof(mechsim_msg_CvtState),
               {MECHSIM_F64(mechsim_msg_CvtState, input_speed),
                MECHSIM_F64(mechsim_msg_CvtState, output_speed),
                MECHSIM_F64(mechsim_msg_CvtState, output_acceleration),
                MECHSIM_F64(mechsim_msg_CvtState, ratio),
                MECHSIM_F64(mechsim_msg_CvtState, ratio_setting),
                MECHSIM_F64(mechsim_msg_CvtState, ratio_command),
                MECHSIM_F64(mechsim_msg_CvtState, motor_torque),
                MECHSIM_F64(mechsim_msg_CvtState, belt_torque),
                MECHSIM_F64(mechsim_msg_CvtState, input_torque),
                MECHSIM_F64(mechsim_msg_CvtState, output_torque),
                MECHSIM_F64(mechsim_msg_CvtState, eta_PB),
                MECHSIM_F64(mechsim_msg_CvtState, eta_SYS),
                MECHSIM_F64(mechsim_msg_CvtState, clamping_force),
                MECHSIM_F64(mechsim_msg_CvtState, slip_margin),
                MECHSIM_F64(mechsim_msg_CvtState, sigma_1),
                MECHSIM_F64(mechsim_msg_CvtState, sigma_2),
                MECHSIM_F64(mechsim_msg_CvtState, sigma_3),
                MECHSIM_F64(mechsim_msg_CvtState, sigma_4),
                MECHSIM_F64(mechsim_msg_CvtState, belt_loss),
                MECHSIM_F64(mechsim_msg_CvtState, bearing_loss),
                MECHSIM_F64(mechsim_msg_CvtState, flags),
                MECHSIM_FLAG(mechsim_msg_CvtState, gross_slip),
                MECHSIM_FLAG(mechsim_msg_CvtState, torque_reversal),
                MECHSIM_FLAG(mechsim_msg_CvtState, outside_model)}});
#define MECHSIM_LEVELS(X) X(1) X(2) X(3) X(4) X(5) X(6) X(7) X(8) X(9) X(10) X(11) X(12) X(13) X(14) X(15) X(16)
#define MECHSIM_PREDICTED(j) MECHSIM_F64(mechsim_msg_CouplingPrediction, predicted_angle_##j),
#define MECHSIM_SENSITIVITY(j) MECHSIM_F64(mechsim_msg_CouplingPrediction, sensitivity_##j),
  b.push_back({find_topic_type("CouplingPrediction"), &mechsim_msg_CouplingPrediction_desc,
               sizeof(mechsim_msg_CouplingPrediction),
               {MECHSIM_F64(mechsim_msg_CouplingPrediction, angle), MECHSIM_F64(mechsim_msg_CouplingPrediction, assumed_torque),
                MECHSIM_F64(mechsim_msg_CouplingPrediction, levels), MECHSIM_LEVELS(MECHSIM_PREDICTED)
                MECHSIM_LEVELS(MECHSIM_SENSITIVITY)}});
#undef MECHSIM_PREDICTED
#undef MECHSIM_SENSITIVITY
#undef MECHSIM_LEVELS
  b.push_back({find_topic_type("StepProposal"), &mechsim_msg_StepProposal_desc, sizeof(mechsim_msg_StepProposal),
               {MECHSIM_F64(mechsim_msg_StepProposal, step_length), MECHSIM_FLAG(mechsim_msg_StepProposal, event),
                MECHSIM_F64(mechsim_msg_StepProposal, event_time), MECHSIM_F64(mechsim_msg_StepProposal, error_estimate),
                MECHSIM_F64(mechsim_msg_StepProposal, state_event_time)}});
  for (const auto& binding : b)
    if (binding.type == nullptr || binding.slots.size() != binding.type->fields.size())
      throw std::logic_error("cyclone binding does not match topic_types.cpp");
  return b;
}
#undef MECHSIM_F64
#undef MECHSIM_FLAG
}  // namespace

const CycloneType& cyclone_type(const TopicType& type) {
  static const std::vector<CycloneType> bindings = make_bindings();
  for (const auto& b : bindings)
    if (b.type == &type) return b;
  throw std::runtime_error("no Cyclone DDS binding for topic type " + type.idl_name);
}

}  // namespace mechsim::transport::cyclone
