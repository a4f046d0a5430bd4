// The cam shaft as a block (spec cam.md §1, §2, §4): turns the cam and publishes the lift
// law and the pressure angle at the current angle.
//
// Two kinds of drive (shaft_drive.h):
//  - constant speed (an ideal speed source): no state, θ = θ0 + ω t;
//  - a torque source (constant torque or a motor line) on the shaft inertia I (shaft +
//    flywheel): states θ, ω with
//        (I + J_r) ω̇ = T_drive(ω) − M_rest
//    where J_r = m S'² is the inertia a rigid follower reflects onto the shaft and M_rest
//    the torque of all its other forces. Carrying J_r here, on the side that integrates ω,
//    breaks the algebraic loop a rigid follower would otherwise close across the cut
//    (docs/cam-dynamics.md): the follower's M_rest and J_r do not depend on ω̇.
#pragma once

#include <optional>

#include "mechsim/models/block.h"
#include "mechsim/models/cam/motion_law.h"
#include "mechsim/models/cam/shaft_drive.h"
#include "mechsim/models/cam/shaft_segment.h"

namespace mechsim::models::cam {

struct CamShaftParams {
  MotionLaw law;
  double pitch_radius;   // R0, m
  double eccentricity;   // e, m
  double speed;          // rad/s: the constant speed, or with a torque drive the nominal
                         // (design) speed ω_avg and the default initial speed
  double initial_angle;  // rad, at t = 0
  ShaftDrive drive{};                   // default: constant speed
  double inertia_kgm2 = 0.0;            // I: shaft + flywheel (torque drives, > 0)
  std::optional<double> initial_speed{};  // rad/s at t = 0 (torque drives); default: speed
  // > 0: the shaft is driven by another shaft through a rigid, lossless gear of this ratio
  // (ω_drive / ω_cam). The driving side integrates the speed: the cam shaft reads the
  // driving shaft's speed and acceleration and hands back its load torque and its inertia
  // (shaft, flywheel and the follower's reflected inertia) reflected through the gear.
  double gear_ratio = 0.0;
  // Set: the shaft is a station of a line shaft, driven by the upstream shaft through this
  // elastic segment (docs/line-shaft.md). States θ, ω on the shaft's own inertia (> 0).
  std::optional<ShaftSegment> segment{};
};

// Inputs: load_torque (N m, default 0: the torque the follower demands except its
// reflected-inertia part, i.e. the follower's drive_torque_rest), reflected_inertia
// (kg m², default 0). Outputs: angle, speed, lift, lift_d1, lift_d2, pressure_angle,
// shaft_torque (torque the drive delivers: the load torque for a speed source, T_drive(ω)
// for a torque source), drive_power (= shaft_torque · speed), acceleration (ω̇; 0 at
// constant speed). Feedthrough: at constant speed shaft_torque and drive_power from
// load_torque; with a torque drive only acceleration, from both inputs.
//
// Driven through a gear (gear_ratio g > 0, docs/press-line.md): one state θ with
// θ' = ω_drive/g. Extra inputs drive_speed and drive_acceleration (the driving shaft's);
// extra outputs drive_load_torque = M_rest/g and drive_load_inertia = (I + J_r)/g², which
// the driving side carries in its own equation (as the shaft carries J_r of the follower),
// so no algebraic loop closes across the gear. shaft_torque is then the torque the gear
// delivers, M_rest + (I + J_r) ω̇. Every mode also outputs kinetic_energy = ½ I ω² (the
// shaft and flywheel; 0 for a speed source, which has no inertia).
//
// A shaft driven through a gear or a segment has the input downstream_torque (N m, default
// 0, the last input): the torque the next elastic segment of a line shaft takes from this
// shaft (that segment's drive_load_torque). It adds to the load torque: a gear hands it back
// to the driving shaft, a segment-driven shaft's ω̇ pays for it.
//
// Driven through an elastic segment (segment set, docs/line-shaft.md): states θ, ω and the
// segment's twist q (0 at t = 0) with
//     (I + J_r) ω̇ = T_seg − M_rest − T_down,   q̇ = ω_u − ω,   T_seg = k q + c q̇
// from the input drive_speed ω_u (the upstream shaft's, required). The twist is integrated
// from the speeds rather than taken from the upstream angle: a co-simulation holds a partner's
// first sample over the first step, and a held angle would twist a line turning at speed by
// ω H at once (2 kN m on the shipped line); a held speed makes no such jump.
// shaft_torque = drive_load_torque = T_seg (the torque the segment delivers here and takes
// from upstream); extra outputs segment_energy = ½ k q² and segment_damping_power = c q̇².
class CamShaftBlock : public Block {
 public:
  explicit CamShaftBlock(CamShaftParams params);

  void initial_state(double t0, std::span<double> x) const override;
  void derivatives(double t, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override;
  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const CamShaftParams& params() const { return params_; }
  bool has_dynamic_drive() const { return params_.drive.is_torque_source(); }
  // At constant speed (neither driven nor with a torque-source drive) the angle is a
  // function of time: the followers' load boundaries become times (Block::angle_events).
  std::optional<UniformRotation> uniform_rotation() const override;
  // The joints of the lift law (every piece's start, dwells included).
  std::vector<double> angle_law_changes() const override;
  bool is_driven() const { return params_.gear_ratio > 0.0; }
  bool is_segment_driven() const { return params_.segment.has_value(); }
  // ω̇ of a torque drive at speed ω under the given load (0 for a speed source).
  double angular_acceleration(double speed, double load_torque_rest, double reflected_inertia,
                              double downstream_torque = 0.0) const;

 private:
  // ω̇ of a segment-driven shaft under the segment's torque and the inputs' loads.
  double segment_acceleration(double segment_torque, std::span<const double> u) const;

  CamShaftParams params_;
  // Input indices of the driven modes (-1: not declared).
  int in_drive_speed_ = -1, in_drive_acceleration_ = -1, in_downstream_torque_ = -1;
};

}  // namespace mechsim::models::cam
