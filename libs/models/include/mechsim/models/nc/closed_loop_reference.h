// The whole NC position loop of spec nc_slide.md §3 as one block, for references and tests:
// servo amplifier + motor–tacho + coupling C_kopp, d_k + slide (two-mass by default),
// wired from the very blocks the nodes run, with the coupling evaluated once here as the
// composer would. With the continuous amplifier and the two-mass slide it has the spec's
// eleven states: [z, U_Tf | i_a, ω1, ω2, θ, φ1 | φ_a, φ_b, ω_a, ω_b].
//
// Ports: no inputs (internal interpolator) or position_setpoint [m] (external setpoint);
// outputs slide_position [m], slide_speed [m/s], spindle_angle [rad], motor_speed [rad/s],
// armature_current [A], armature_voltage [V], tacho_voltage [V], coupling_torque [N m],
// position_reference [m], velocity_error [V], saturated [1]. The sample time and discrete
// state are the amplifier's.
#pragma once

#include "mechsim/models/block.h"
#include "mechsim/models/nc/coupling.h"
#include "mechsim/models/nc/motor_tacho_block.h"
#include "mechsim/models/nc/servo_amplifier_block.h"
#include "mechsim/models/nc/slide_block.h"

namespace mechsim::models::nc {

struct ClosedLoopOptions {
  ServoAmplifierParams amplifier;
  MotorTachoParams motor;
  CouplingParams coupling;
  SlideBlockOptions slide;  // its coupling_input is forced to torque: the coupling is here
};

class ClosedLoopReference final : public Block {
 public:
  explicit ClosedLoopReference(ClosedLoopOptions options = {});

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  double sample_time() const override { return amplifier_.sample_time(); }
  void discrete_update(double t, std::span<double> x, std::span<const double> u) override;
  std::vector<double> save_discrete_state() const override { return amplifier_.save_discrete_state(); }
  void restore_discrete_state(std::span<const double> saved) override {
    amplifier_.restore_discrete_state(saved);
  }

  const ServoAmplifierBlock& amplifier() const { return amplifier_; }
  const MotorTachoBlock& motor() const { return motor_; }
  const SlideBlock& slide() const { return slide_; }
  // Offsets of each part's states in x.
  int amplifier_offset() const { return 0; }
  int motor_offset() const { return amplifier_.num_states(); }
  int slide_offset() const { return amplifier_.num_states() + motor_.num_states(); }

 private:
  // Every sub-block's inputs and outputs at (t, x, u).
  struct Signals {
    double amplifier_in[3], amplifier_out[5], motor_in[2], motor_out[4], slide_in[1], slide_out[5];
  };
  void evaluate(double t, std::span<const double> x, std::span<const double> u, Signals& s) const;
  std::span<const double> part(std::span<const double> x, int offset, const Block& block) const {
    return x.subspan(offset, block.num_states());
  }

  static SlideBlockOptions torque_coupled(SlideBlockOptions slide);

  CouplingParams coupling_;
  ServoAmplifierBlock amplifier_;
  MotorTachoBlock motor_;
  SlideBlock slide_;
  struct SubPorts {
    int amp_tacho, amp_angle, amp_setpoint, amp_voltage, amp_reference, amp_error, amp_saturated;
    int motor_voltage, motor_load, motor_tacho, motor_angle, motor_speed, motor_current;
    int slide_torque, slide_angle, slide_speed, slide_position, slide_velocity, slide_coupling;
  } p_;
  struct Outputs {
    int slide_position, slide_speed, spindle_angle, motor_speed, armature_current, armature_voltage,
        tacho_voltage, coupling_torque, position_reference, velocity_error, saturated;
  } out_;
  int in_setpoint_ = -1;
};

}  // namespace mechsim::models::nc
