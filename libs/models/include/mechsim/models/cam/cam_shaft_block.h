// The cam shaft as a block: a constant-speed drive turning the cam, publishing the lift
// law and the pressure angle at the current angle (spec cam.md §1, §2, §4).
#pragma once

#include "mechsim/models/block.h"
#include "mechsim/models/cam/motion_law.h"

namespace mechsim::models::cam {

struct CamShaftParams {
  MotionLaw law;
  double pitch_radius;   // R0, m
  double eccentricity;   // e, m
  double speed;          // rad/s, constant
  double initial_angle;  // rad, at t = 0
};

// No state: θ(t) = initial_angle + speed · t (initial_angle is the angle at t = 0). Input: load_torque (N m, default 0: the torque the
// follower demands). Outputs: angle, speed, lift, lift_d1, lift_d2, pressure_angle,
// shaft_torque (= load_torque), drive_power (= shaft_torque · speed); only the last two
// have feedthrough.
class CamShaftBlock : public Block {
 public:
  explicit CamShaftBlock(CamShaftParams params);

  void calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                    std::span<double> y) const override;

  const CamShaftParams& params() const { return params_; }

 private:
  CamShaftParams params_;
};

}  // namespace mechsim::models::cam
