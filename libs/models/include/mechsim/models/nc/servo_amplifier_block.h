// Servo amplifier of the NC position loop (spec nc_slide.md §3): position loop, PI velocity
// loop on the filtered tacho voltage, ±50 V output with back-calculation anti-windup.
//
//   φ_ref = x_ref / r,  r = lead/2π          (x_ref: interpolator or position_setpoint)
//   e     = α (K_v (φ_ref − φ_a) + k_ff dφ_ref/dt) − U_Tf     (φ_a: spindle angle)
//   u     = K_sv e + z,     U_a = clamp(u, lo, hi)
//   dz/dt = (K_sv/T_i) e + (U_a − u)/T_t
//   τ_f dU_Tf/dt = U_T − U_Tf                                   (analog tacho filter)
//
// [lo, hi] = [−U_max, U_max], narrowed by the optional current limit. The limit is a
// voltage clamp around the back-emf estimated from the (unfiltered) tacho voltage,
//   E = (c/α) U_T,   lo = E − R_a I_max,   hi = E + R_a I_max,
// which holds |i_a| at I_max once the electrical transient (L_a/R_a = 0.24 ms) has passed.
// It needs no armature-current feedback, so it adds no fast loop across the
// amplifier–motor cut (a proportional current feedback would, with a time constant of tens
// of µs); the amplifier therefore has no armature_current input.
//
// Velocity feed-forward (k_ff, 0..1) uses the interpolator's velocity; an external
// position_setpoint carries no velocity, so feed-forward acts only with the internal one.
//
// States (both modes): integrator z [V], filtered_tacho_voltage U_Tf [V].
// Continuous (sample_time = 0): the law above acts on the inputs as they are.
// Sampled (sample_time = T > 0): sample-and-hold on both sides. At t_k = t0 + k T,
// discrete_update samples tacho_voltage, spindle_angle and the setpoint (interpolator or
// position_setpoint) and computes U_a(t_k) from them and z(t_k), U_Tf(t_k); U_a is held
// until t_k+1 (zero-order hold, no computation delay). Between samples z and U_Tf keep
// evolving with the held inputs; the anti-windup term compares with the clamp of the
// running u(t), so it stays silent while the controller is unsaturated. This is the
// amplifier as a co-simulation participant exchanging every T, and it reproduces the
// coupling study's sampled reference (notes/coupling-facts.md: at T = 1 ms the 0.1 mm step
// rises 0.7 % slower and settles 3 % sooner). The samples and the held outputs are the
// discrete state (save/restore_discrete_state).
//
// Ports                          unit   feedthrough (continuous; none when sampled)
//   in  tacho_voltage            V      required
//   in  spindle_angle            rad    required
//   in  position_setpoint        m      required, only with SetpointSource::external
//   out armature_voltage         V      spindle_angle, position_setpoint, tacho_voltage (current limit)
//   out position_reference       m      position_setpoint
//   out following_error          m      spindle_angle, position_setpoint: reference − spindle_angle·lead/2π
//   out velocity_error           V      spindle_angle, position_setpoint
//   out saturated                1      as armature_voltage; 1 while U_a != u
#pragma once

#include <vector>

#include "mechsim/models/block.h"
#include "mechsim/models/nc/setpoint_profile.h"

namespace mechsim::models::nc {

enum class SetpointSource { internal, external };

struct CurrentLimitParams {
  bool enabled = false;
  double max_current = 30.0;               // I_max [A] (the shipped saturating scenes use 30 A)
  double armature_resistance = 0.27921;    // R_a of the driven motor [Ω]
  double back_emf_per_tacho_volt = 0.2 / 0.0496;  // c/α of the driven motor [V/V]
};

struct ServoAmplifierParams {
  double position_gain = 40.0;           // K_v [1/s]
  double velocity_gain = 10.0;           // K_sv [V/V]
  double integral_time = 0.01;           // T_i [s]
  double antiwindup_time = 5e-3;         // T_t [s]
  double tacho_filter_time = 0.3e-3;     // τ_f [s]
  double voltage_limit = 50.0;           // U_max [V]
  double tacho_constant = 0.0496;        // α [V s/rad]
  double lead = 0.005;                   // spindle lead [m/rev]
  double velocity_feedforward = 0.0;     // k_ff [-]
  double sample_time = 0.0;              // T [s]; 0 = continuous
  CurrentLimitParams current_limit;
  SetpointSource setpoint_source = SetpointSource::internal;
  // Where the position is measured: on the spindle (the CNC 200's indirect system, input
  // spindle_angle) or on the motor shaft (input motor_angle: a motor bench without slide).
  bool measure_on_motor = false;
  SetpointProfile setpoint;              // used with SetpointSource::internal
};

class ServoAmplifierBlock final : public Block {
 public:
  explicit ServoAmplifierBlock(ServoAmplifierParams params = {});

  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  double sample_time() const override { return params_.sample_time; }
  // The internal setpoint's corners (none with an external setpoint).
  std::vector<double> scheduled_events(double t0, double t_end) const override;
  void discrete_update(double t, std::span<double> x, std::span<const double> u) override;
  std::vector<double> save_discrete_state() const override;
  void restore_discrete_state(std::span<const double> saved) override;

  const ServoAmplifierParams& params() const { return params_; }
  // Back to the sampled controller's initial discrete state (zeros), for a new run with
  // the same object; initial_state() is const and cannot do it.
  void reset_discrete_state() { held_ = {}; }

 private:
  struct Measured {  // what the law reads from outside: inputs and setpoint
    double tacho_voltage = 0, spindle_angle = 0, reference = 0, reference_velocity = 0;
  };
  struct Law {
    double velocity_error, unclamped, voltage, integrator_rate;
    bool saturated;
  };
  Measured measure(double t, std::span<const double> u) const;
  Law evaluate(const Measured& m, double integrator, double filtered_tacho) const;
  bool sampled() const { return params_.sample_time > 0; }

  ServoAmplifierParams params_;
  struct Held {  // the sampled controller's discrete state: last samples and held outputs
    Measured sample;
    double voltage = 0, velocity_error = 0, saturated = 0;
  } held_;
  static constexpr std::size_t held_size = 7;
  struct Inputs {
    int tacho_voltage, spindle_angle, position_setpoint = -1;
  } in_;
  struct Outputs {
    int armature_voltage, position_reference, following_error, velocity_error, saturated;
  } out_;
  struct States {
    int integrator, filtered_tacho_voltage;
  } st_;
};

}  // namespace mechsim::models::nc
