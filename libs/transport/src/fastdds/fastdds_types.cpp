#include "fastdds_types.h"

#include <mutex>
#include <stdexcept>
#include <string>

#include "fastddsgen/camPubSubTypes.h"
#include "fastddsgen/couplingPubSubTypes.h"
#include "fastddsgen/cvtPubSubTypes.h"
#include "fastddsgen/followerPubSubTypes.h"
#include "fastddsgen/scalePubSubTypes.h"
#include "fastddsgen/fmuPubSubTypes.h"
#include "fastddsgen/servoPubSubTypes.h"
#include "fastddsgen/slidePubSubTypes.h"
#include "fastddsgen/stepPubSubTypes.h"
#include "fastddsgen/tachoPubSubTypes.h"

namespace mechsim::transport::fastdds {

namespace {

// One field of a generated class, reached through its mutable accessor.
template <class Msg>
struct Slot {
  const char* name;
  double& (Msg::*f64)();
  bool& (Msg::*flag)();
};

template <class Msg>
class BoundSample final : public FastSample {
 public:
  explicit BoundSample(const std::vector<Slot<Msg>>& slots) : slots_(slots) {}
  void* data() override { return &msg_; }
  void store(const SampleHeader& header, std::span<const double> values) override {
    msg_.header().run_id(header.run_id);
    msg_.header().step(header.step);
    msg_.header().t(header.t);
    for (std::size_t i = 0; i < slots_.size(); ++i) {
      if (slots_[i].f64)
        (msg_.*slots_[i].f64)() = values[i];
      else
        (msg_.*slots_[i].flag)() = values[i] != 0.0;
    }
  }
  void load(SampleHeader& header, std::vector<double>& values) override {
    header = {msg_.header().run_id(), msg_.header().step(), msg_.header().t()};
    values.resize(slots_.size());
    for (std::size_t i = 0; i < slots_.size(); ++i)
      values[i] = slots_[i].f64 ? (msg_.*slots_[i].f64)() : ((msg_.*slots_[i].flag)() ? 1.0 : 0.0);
  }

 private:
  const std::vector<Slot<Msg>>& slots_;
  Msg msg_;
};

template <class Msg, class PubSub>
class Binding final : public FastType {
 public:
  Binding(const char* short_name, std::vector<Slot<Msg>> slots) : type_(find_topic_type(short_name)), slots_(std::move(slots)) {
    // The slots must mirror topic_types.cpp field by field, names included.
    if (type_ == nullptr || slots_.size() != type_->fields.size())
      throw std::logic_error(std::string("Fast DDS binding of ") + short_name + " does not match topic_types.cpp");
    for (std::size_t i = 0; i < slots_.size(); ++i)
      if (type_->fields[i].name != slots_[i].name ||
          (type_->fields[i].kind == FieldKind::boolean) != (slots_[i].flag != nullptr))
        throw std::logic_error(std::string("Fast DDS binding of ") + short_name + ": field " + std::to_string(i) + " is " +
                               slots_[i].name + ", topic_types.cpp says " + type_->fields[i].name);
  }
  const TopicType& topic_type() const override { return *type_; }
  eprosima::fastdds::dds::TopicDataType* make_type_support() const override { return new PubSub(); }
  std::unique_ptr<FastSample> make_sample() const override { return std::make_unique<BoundSample<Msg>>(slots_); }

 private:
  const TopicType* type_;
  std::vector<Slot<Msg>> slots_;
};

// An FMU participant's topic type (layout sequences): its fields split by kind into
// FmuOutputs' three sequences, in field order.
class FmuOutputsSample final : public FastSample {
 public:
  explicit FmuOutputsSample(const TopicType& type) : type_(type), at_(sequence_positions(type)) {
    for (const auto& f : type.fields) (f.kind == FieldKind::f64 ? reals_ : f.kind == FieldKind::i32 ? integers_ : booleans_)++;
  }
  void* data() override { return &msg_; }
  void store(const SampleHeader& header, std::span<const double> values) override {
    msg_.header().run_id(header.run_id);
    msg_.header().step(header.step);
    msg_.header().t(header.t);
    msg_.reals().resize(reals_);
    msg_.integers().resize(integers_);
    msg_.booleans().resize(booleans_);
    pack_sequences(type_, at_, values.data(), msg_.reals(), msg_.integers(), msg_.booleans());
  }
  void load(SampleHeader& header, std::vector<double>& values) override {
    header = {msg_.header().run_id(), msg_.header().step(), msg_.header().t()};
    unpack_sequences(type_, at_, msg_.reals(), msg_.reals().size(), msg_.integers(), msg_.integers().size(), msg_.booleans(),
                     msg_.booleans().size(), values);
  }

 private:
  const TopicType& type_;
  std::vector<std::size_t> at_;
  std::size_t reals_ = 0, integers_ = 0, booleans_ = 0;
  mechsim::msg::FmuOutputs msg_;
};

class FmuOutputsBinding final : public FastType {
 public:
  explicit FmuOutputsBinding(const TopicType& type) : type_(type) {}
  const TopicType& topic_type() const override { return type_; }
  eprosima::fastdds::dds::TopicDataType* make_type_support() const override { return new mechsim::msg::FmuOutputsPubSubType(); }
  std::unique_ptr<FastSample> make_sample() const override { return std::make_unique<FmuOutputsSample>(type_); }

 private:
  TopicType type_;  // a copy: FMU topic types are made per plan
};

#define MECHSIM_F64(Msg, field) Slot<Msg>{#field, static_cast<double& (Msg::*)()>(&Msg::field), nullptr}
#define MECHSIM_FLAG(Msg, field) Slot<Msg>{#field, nullptr, static_cast<bool& (Msg::*)()>(&Msg::field)}

using namespace mechsim::msg;

std::vector<std::unique_ptr<FastType>> make_bindings() {
  std::vector<std::unique_ptr<FastType>> b;
  b.push_back(std::make_unique<Binding<CamState, CamStatePubSubType>>(
      "CamState", std::vector<Slot<CamState>>{
                      MECHSIM_F64(CamState, angle), MECHSIM_F64(CamState, speed), MECHSIM_F64(CamState, acceleration),
                      MECHSIM_F64(CamState, lift), MECHSIM_F64(CamState, lift_d1), MECHSIM_F64(CamState, lift_d2),
                      MECHSIM_F64(CamState, pressure_angle), MECHSIM_F64(CamState, shaft_torque),
                      MECHSIM_F64(CamState, drive_power), MECHSIM_F64(CamState, drive_load_torque),
                      MECHSIM_F64(CamState, drive_load_inertia)}));
  b.push_back(std::make_unique<Binding<FollowerState, FollowerStatePubSubType>>(
      "FollowerState",
      std::vector<Slot<FollowerState>>{
          MECHSIM_F64(FollowerState, position), MECHSIM_F64(FollowerState, velocity),
          MECHSIM_F64(FollowerState, acceleration), MECHSIM_F64(FollowerState, contact_force),
          MECHSIM_FLAG(FollowerState, contact), MECHSIM_F64(FollowerState, lift_off_count),
          MECHSIM_F64(FollowerState, drive_torque), MECHSIM_F64(FollowerState, drive_torque_rest),
          MECHSIM_F64(FollowerState, reflected_inertia), MECHSIM_F64(FollowerState, spring_force),
          MECHSIM_F64(FollowerState, load_force), MECHSIM_F64(FollowerState, inertia_force)}));
  b.push_back(std::make_unique<Binding<ServoCommand, ServoCommandPubSubType>>(
      "ServoCommand", std::vector<Slot<ServoCommand>>{
                          MECHSIM_F64(ServoCommand, armature_voltage), MECHSIM_F64(ServoCommand, position_reference),
                          MECHSIM_F64(ServoCommand, following_error), MECHSIM_F64(ServoCommand, velocity_error),
                          MECHSIM_FLAG(ServoCommand, saturated)}));
  b.push_back(std::make_unique<Binding<TachoState, TachoStatePubSubType>>(
      "TachoState", std::vector<Slot<TachoState>>{
                        MECHSIM_F64(TachoState, tacho_voltage), MECHSIM_F64(TachoState, motor_angle),
                        MECHSIM_F64(TachoState, motor_speed), MECHSIM_F64(TachoState, armature_current),
                        MECHSIM_F64(TachoState, coupling_torque)}));
  b.push_back(std::make_unique<Binding<SlideState, SlideStatePubSubType>>(
      "SlideState", std::vector<Slot<SlideState>>{
                        MECHSIM_F64(SlideState, spindle_angle), MECHSIM_F64(SlideState, spindle_speed),
                        MECHSIM_F64(SlideState, slide_position), MECHSIM_F64(SlideState, slide_speed),
                        MECHSIM_F64(SlideState, coupling_torque)}));
  b.push_back(std::make_unique<Binding<ScaleReading, ScaleReadingPubSubType>>(
      "ScaleReading", std::vector<Slot<ScaleReading>>{MECHSIM_F64(ScaleReading, measured_position),
                                                      MECHSIM_F64(ScaleReading, measurement_error)}));
  b.push_back(std::make_unique<Binding<CvtState, CvtStatePubSubType>>(
      "CvtState", std::vector<Slot<CvtState>>{
          MECHSIM_F64(CvtState, input_speed),
          MECHSIM_F64(CvtState, output_speed),
          MECHSIM_F64(CvtState, output_acceleration),
          MECHSIM_F64(CvtState, ratio),
          MECHSIM_F64(CvtState, ratio_setting),
          MECHSIM_F64(CvtState, ratio_command),
          MECHSIM_F64(CvtState, motor_torque),
          MECHSIM_F64(CvtState, belt_torque),
          MECHSIM_F64(CvtState, input_torque),
          MECHSIM_F64(CvtState, output_torque),
          MECHSIM_F64(CvtState, eta_PB),
          MECHSIM_F64(CvtState, eta_SYS),
          MECHSIM_F64(CvtState, clamping_force),
          MECHSIM_F64(CvtState, slip_margin),
          MECHSIM_F64(CvtState, sigma_1),
          MECHSIM_F64(CvtState, sigma_2),
          MECHSIM_F64(CvtState, sigma_3),
          MECHSIM_F64(CvtState, sigma_4),
          MECHSIM_F64(CvtState, belt_loss),
          MECHSIM_F64(CvtState, bearing_loss),
          MECHSIM_F64(CvtState, flags),
          MECHSIM_FLAG(CvtState, gross_slip),
          MECHSIM_FLAG(CvtState, torque_reversal),
          MECHSIM_FLAG(CvtState, outside_model)}));
#define MECHSIM_LEVELS(X) X(1) X(2) X(3) X(4) X(5) X(6) X(7) X(8) X(9) X(10) X(11) X(12) X(13) X(14) X(15) X(16)
#define MECHSIM_PREDICTED(j) MECHSIM_F64(CouplingPrediction, predicted_angle_##j),
#define MECHSIM_SENSITIVITY(j) MECHSIM_F64(CouplingPrediction, sensitivity_##j),
  b.push_back(std::make_unique<Binding<CouplingPrediction, CouplingPredictionPubSubType>>(
      "CouplingPrediction", std::vector<Slot<CouplingPrediction>>{
                                MECHSIM_F64(CouplingPrediction, angle), MECHSIM_F64(CouplingPrediction, assumed_torque),
                                MECHSIM_F64(CouplingPrediction, levels), MECHSIM_LEVELS(MECHSIM_PREDICTED)
                                MECHSIM_LEVELS(MECHSIM_SENSITIVITY)}));
#undef MECHSIM_PREDICTED
#undef MECHSIM_SENSITIVITY
#undef MECHSIM_LEVELS
  b.push_back(std::make_unique<Binding<StepProposal, StepProposalPubSubType>>(
      "StepProposal", std::vector<Slot<StepProposal>>{
                          MECHSIM_F64(StepProposal, step_length), MECHSIM_FLAG(StepProposal, event),
                          MECHSIM_F64(StepProposal, event_time), MECHSIM_F64(StepProposal, error_estimate),
                          MECHSIM_F64(StepProposal, state_event_time)}));
  return b;
}
#undef MECHSIM_F64
#undef MECHSIM_FLAG

}  // namespace

const FastType& fast_type(const TopicType& type) {
  if (type.layout == TopicLayout::sequences) {
    // One binding per distinct FMU topic type, kept for the process's life.
    static std::mutex mutex;
    static std::vector<std::unique_ptr<FastType>> fmu_bindings;
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& b : fmu_bindings)
      if (b->topic_type().same_as(type)) return *b;
    return *fmu_bindings.emplace_back(std::make_unique<FmuOutputsBinding>(type));
  }
  static const std::vector<std::unique_ptr<FastType>> bindings = make_bindings();
  for (const auto& b : bindings)
    if (&b->topic_type() == &type) return *b;
  throw std::runtime_error("no Fast DDS binding for topic type " + type.idl_name);
}

}  // namespace mechsim::transport::fastdds
