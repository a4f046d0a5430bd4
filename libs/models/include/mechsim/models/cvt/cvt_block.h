// Time-domain block of the push-belt CVT with its input drive (spec cvt.md §8.4), the block of
// the `cvt` node type (docs/cvt.md, docs/press-line.md). The belt is the stationary L1/L0 map
// evaluated at every call; the dynamics around it are assumptions of ours:
//
//   motor line on the input shaft        T_M = T_stall (1 − ω_C/ω_0)
//   input shaft (motor + C)              J_C dω_C/dt = T_M − T_1,   T_1 = T_C + T_Lprim
//   disc shaft, ω_D = i(s) ω_C            (J_D + J_L) dω_D/dt = T_2 − T_P,   T_2 = η_PB T_C/i − T_Lsec
//   ratio actuator (first order)         ds/dt = (s_cmd(t) − s)/τ_s
//
// J_L (input load_inertia) is an inertia the load hands over to be carried on the disc shaft
// (a cam shaft driven through a gear: its shaft, flywheel and follower, reflected); it may vary
// in time: its ½ J̇_L ω_D² belongs to the load's torque T_P, as with the follower's m S'².
// Eliminating T_C (ω̇_D = i ω̇_C + i'(s) ṡ ω_C, the term a changing ratio adds), J' = J_D + J_L:
//   (J_C + i² J'/η_PB) ω̇_C = T_M − T_Lprim − i (T_Lsec + T_P)/η_PB − J' i i' ṡ ω_C/η_PB
// η_PB and the bearing losses depend on T_C: a short fixed point from the quasi-static guess.
// Where the belt state is outside the model (gross slip, reversal, a bad input) the block
// carries on with a lossless belt and says so in `flags`; it never stops the run.
//
// s_cmd is the ratio_command input, or, when the params give a schedule, the schedule's
// piecewise-linear value at t (a step is two points at the same time).
//
// Ports                   unit    feedthrough
//   in  ratio_command      m       default s0 (not declared with a schedule)
//   in  load_torque        N m     default 0      T_P on the disc shaft
//   in  load_inertia       kg m²   default 0      J_L carried on the disc shaft
//   out input_speed, output_speed, ratio, ratio_setting, ratio_command, motor_torque,
//       motor_power (T_M ω_C), kinetic_energy (½J_C ω_C² + ½J_D ω_D², without J_L)
//   out output_acceleration, belt_torque T_C, input_torque T_1, output_torque T_2, eta_PB,
//       eta_SYS, clamping_force, slip_margin (v_KD), sigma_1..sigma_4, belt_loss,
//       bearing_loss [W], flags, gross_slip, torque_reversal, outside_model (0/1):
//       feedthrough from load_torque and load_inertia
// belt_loss and bearing_loss are the powers the equations above dissipate (lossless belt:
// 0), so that motor power = load power + losses + d/dt kinetic energy holds exactly.
// Every output is finite: outside the model η_PB is the lossless belt's 1, η_SYS the
// equations' power ratio, and a number the model does not give is 0 (flags say which).
// States: input_speed [rad/s], ratio_setting [m].
#pragma once

#include <utility>
#include <vector>

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
  // Setpoint schedule of the ratio actuator: (t [s], s [m]) points, times non-decreasing;
  // held before the first and after the last point. Empty: the ratio_command input.
  std::vector<std::pair<double, double>> ratio_schedule;
  // Belt map tabulated at construction (safety-factor clamping only): the chosen level is
  // evaluated on an s × T_C × ω_C grid over the shape table and the validated range, and
  // η_PB, F_K/(T/r), v_KD and σ1..σ4 are interpolated (trilinear, clamped at the edges);
  // the bearing losses stay closed form. A step then costs no map evaluation: an L1
  // evaluation costs ~0.7 ms, far too much for every right-hand side of a time run.
  bool belt_table = false;
  int table_s_points = 11, table_torque_points = 6, table_speed_points = 5;
  // Clamping actuator lag (belt_table only): > 0 adds the state clamping_force F with
  // dF/dt = (F_cmd − F)/τ_F, F_cmd the map's F_K at v_K. The belt then runs at F: the slip
  // margin scales with F/F_cmd, the bearings see F, and F below F_cmd/v_K (the need at
  // v_K = 1) is gross slip (flagged, lossless belt). 0: F = F_cmd at every instant.
  double clamp_time_constant = 0.0;  // τ_F [s]
  double F_K0 = -1.0;                // initial F [N]; < 0: the command at the initial state, no load
};

class CvtBlock final : public Block {
 public:
  explicit CvtBlock(CvtBlockParams params = {});

  void initial_state(double t0, std::span<double> x) const override;
  // The ratio schedule's points (a jump where two share a time, a kink elsewhere).
  std::vector<double> scheduled_events(double t0, double t_end) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const CvtBlockParams& params() const { return p_; }

  struct Solution {
    CvtResult belt;
    double T_M = 0.0, omega_dot = 0.0, s_dot = 0.0, di_ds = 0.0;
    double s_cmd = 0.0;       // the actuator's setpoint [m]
    double T_C = 0.0;         // belt torque of the equations [N m]
    double eta = 1.0;         // η_PB used (1 outside the model)
    double T_L_prim = 0.0, T_L_sec = 0.0;  // bearing torques used [N m]
    double omega_D_dot = 0.0;
    unsigned flags = 0;       // the model's flags and the block's kBadInput
    double F_cmd = 0.0;       // clamping-force setpoint (the map's F_K) [N]
  };
  // The belt state and the accelerations at (t, x, u).
  Solution solve(double t, std::span<const double> x, std::span<const double> u) const;
  Solution solve(std::span<const double> x, std::span<const double> u) const { return solve(0.0, x, u); }
  // The actuator setpoint at t (schedule or input).
  double ratio_command(double t, std::span<const double> u) const;
  // The belt at (s, ω_C, T_C): the model, or the tabulated map when belt_table is set.
  // Throws CvtInputError on bad input (direct evaluation).
  CvtResult belt(double s, double omega_C, double T_C) const;

 private:
  CvtBlockParams p_;
  mutable CvtModel model_;  // the shape table is built in the constructor: no search at run time
  struct Table {
    int ns = 0, nt = 0, nw = 0;
    double s0 = 0, ds = 0, t0 = 0, dt = 0, w0 = 0, dw = 0;
    static constexpr int kFields = 7;  // η_PB, F_K/(T/r), v_KD, σ1..σ4
    std::vector<double> v;             // [((is·nt + it)·nw + iw)·kFields + f]
  } table_;
  void tabulate_shapes();  // the model's belt-shape table, from the process's cache or searched
  void build_table();      // from the process's cache of belt maps, or compute_table()
  void compute_table();
  CvtResult table_belt(double s, double omega_C, double T_C) const;
  struct {
    int ratio_command = -1, load_torque = -1, load_inertia = -1;
  } in_;
  struct {
    int input_speed, output_speed, ratio, ratio_setting, motor_torque, belt_torque, input_torque, output_torque,
        eta_PB, eta_SYS, clamping_force, slip_margin, sigma1, sigma2, sigma3, sigma4, belt_loss, bearing_loss, flags,
        output_acceleration, ratio_command, motor_power, kinetic_energy, gross_slip, torque_reversal, outside_model;
  } out_{};
  struct {
    int input_speed, ratio_setting, clamping_force = -1;
  } st_{};
  double F_K0_ = 0.0;
  void apply_clamp_lag(CvtResult& r, double F_act, double F_cmd) const;
};

}  // namespace mechsim::models::cvt
