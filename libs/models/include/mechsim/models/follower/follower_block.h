// The rigid, kinetostatic follower as a block (spec cam.md §3): no states, the forces
// follow from the lift law published by the cam shaft.
#pragma once

#include "mechsim/models/block.h"
#include "mechsim/models/follower/kinetostatics.h"

namespace mechsim::models::follower {

// Inputs (required unless noted): angle, speed, lift, lift_d1, lift_d2, pressure_angle,
// acceleration (dω/dt, optional, default 0). Outputs: position, velocity, acceleration,
// contact_force, contact (1 when N ≥ 0), drive_torque, spring_force, load_force,
// inertia_force, then for a dynamic cam shaft drive_torque_rest (the drive torque without
// m S'² ω̇) and reflected_inertia (m S'²), and lift_off_count (always 0: a rigid follower
// cannot fly; N < 0 only says that a real one would); each with feedthrough from the
// inputs it uses. drive_torque_rest and reflected_inertia do not depend on ω̇, which is
// what keeps the loop with a dynamic cam shaft free of direct feedthrough. Energy ports:
// load_power (F_func v: the press work rate), kinetic_energy (½ m v²) and spring_energy
// (F0 S + ½ k S², zero at S = 0).
class FollowerBlock : public Block {
 public:
  explicit FollowerBlock(FollowerParams params);

  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;
  // The load intervals' ends, on the side functional_load() takes as after them.
  std::vector<double> angle_events() const override { return load_boundaries(params_.loads); }
  bool angle_event_reached(double theta, double event) const override { return angle_at_or_past(theta, event); }

  const FollowerParams& params() const { return params_; }

 private:
  FollowerParams params_;
};

}  // namespace mechsim::models::follower
