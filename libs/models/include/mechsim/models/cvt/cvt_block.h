// Time-domain block of the push-belt CVT with its input drive (spec cvt.md §8.4), ready for a
// `cvt` node type (not wired yet). The belt is the stationary L1/L0 map evaluated at every
// call; the dynamics around it are assumptions of ours:
//
//   motor line on the input shaft        T_M = T_stall (1 − ω_C/ω_0)
//   input shaft (motor + C)              J_C dω_C/dt = T_M − T_1,   T_1 = T_C + T_Lprim
//   disc shaft, ω_D = i(s) ω_C            J_D dω_D/dt = T_2 − T_P,   T_2 = η_PB T_C/i − T_Lsec
//   ratio actuator (first order)         ds/dt = (s_cmd − s)/τ_s
//
// Eliminating T_C (ω̇_D = i ω̇_C + i'(s) ṡ ω_C, the term a changing ratio adds):
//   (J_C + i² J_D/η_PB) ω̇_C = T_M − T_Lprim − i (T_Lsec + T_P)/η_PB − J_D i i' ṡ ω_C/η_PB
// η_PB and the bearing losses depend on T_C: a short fixed point from the last T_C. Where the
// belt state is outside the model (gross slip, reversal) the block carries on with a lossless
// belt and says so in `flags`; it never stops the run.
//
// Ports                   unit    feedthrough
//   in  ratio_command      m       default s0
//   in  load_torque        N m     default 0      T_P on the disc shaft (e.g. the cam shaft's reaction)
//   out input_speed        rad/s   —              ω_C
//   out output_speed       rad/s   —              ω_D
//   out ratio              -       —              i_TH
//   out ratio_setting      m       —              s
//   out motor_torque       N m     —              T_M
//   out belt_torque        N m     load_torque    T_C
//   out input_torque       N m     load_torque    T_1
//   out output_torque      N m     load_torque    T_2
//   out eta_PB, eta_SYS    -       load_torque
//   out clamping_force     N       load_torque
//   out slip_margin        -       load_torque    v_KD
//   out sigma_1..sigma_4   Pa      load_torque
//   out belt_loss          W       load_torque
//   out bearing_loss       W       load_torque    T_Lprim ω_C + T_Lsec ω_D
//   out flags              -       load_torque    CvtFlag bit set, as a number
// States: input_speed [rad/s], ratio_setting [m].
#pragma once

#include "mechsim/models/block.h"
#include "mechsim/models/cvt/cvt_model.h"

namespace mechsim::models::cvt {

struct CvtBlockParams {
  CvtParams cvt;
  ClampMode clamp = ClampMode::safety_factor;
  double v_K = 1.0;
  double F_K = 0.0;        // [N], clamp == clamping_force
  Level level = Level::L1;
  double stall_torque = 150.0;   // T_stall of the motor line [N m]
  double no_load_speed = 420.0;  // ω_0 of the motor line [rad/s]
  double J_C = 0.05;             // input side: motor, couplings, C [kg m²]
  double J_D = 0.02;             // output side: disc shaft [kg m²]
  double ratio_time_constant = 0.2;  // τ_s [s]
  double s0 = 30e-3;                 // initial ratio setting [m]
  double omega0 = 0.0;               // initial input speed [rad/s]
  double s_table_min = 5e-3, s_table_max = 55e-3;  // belt shapes tabulated at construction
  int s_table_points = 101;
};

class CvtBlock final : public Block {
 public:
  explicit CvtBlock(CvtBlockParams params = {});

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const CvtBlockParams& params() const { return p_; }

  struct Solution {
    CvtResult belt;
    double T_M = 0.0, omega_dot = 0.0, s_dot = 0.0, di_ds = 0.0;
  };
  // The belt state and the accelerations at (x, u).
  Solution solve(std::span<const double> x, std::span<const double> u) const;

 private:
  CvtBlockParams p_;
  mutable CvtModel model_;  // the shape table is built in the constructor: no search at run time
  struct {
    int ratio_command = -1, load_torque = -1;
  } in_;
  struct {
    int input_speed, output_speed, ratio, ratio_setting, motor_torque, belt_torque, input_torque, output_torque,
        eta_PB, eta_SYS, clamping_force, slip_margin, sigma1, sigma2, sigma3, sigma4, belt_loss, bearing_loss, flags;
  } out_{};
  struct {
    int input_speed, ratio_setting;
  } st_{};
};

}  // namespace mechsim::models::cvt
