// Run-time angle events of an adaptive macro step (docs/accuracy.md, "Events"): where a
// block's law jumps or kinks at a shaft angle (a follower's load boundary, a cam law's
// joint) and the shaft does not turn uniformly (driven through a CVT, or a flywheel under
// load), the plan cannot turn the angle into a time before the run. The node that knows the
// angle predicts, at every step, when the shaft reaches it next, from the shaft's angle,
// speed and acceleration at t_k, and proposes to land a step boundary there.
#pragma once

#include <limits>
#include <span>

namespace mechsim::cosim {

// A shaft's angle [rad, not wrapped], speed [rad/s] and acceleration [rad/s^2] at t [s].
struct ShaftMotion {
  double t = 0.0;
  double angle = 0.0;
  double speed = 0.0;
  double acceleration = 0.0;
  // angle + speed (t' - t) + acceleration (t' - t)^2 / 2: the prediction, exact for a
  // constant acceleration; its error grows with the jerk times (t' - t)^3.
  double angle_at(double t_later) const;
};

struct PredictedAngleEvent {
  double t = std::numeric_limits<double>::infinity();  // +inf: none
  double target = 0.0;  // the angle reached, not wrapped (an event angle + 2 pi n)
};

// The first instant in (after, until] at which a shaft moving on from `motion` reaches one of
// `event_angles` (rad, in [0, 2 pi)), counting only angles past `passed` (not wrapped: the
// last target already landed on, so that one crossing is landed once) and past where the
// shaft is predicted to be at `after`. A shaft that stands or turns back (speed <= 0) or
// whose predicted motion reverses before the angle is reached has none.
PredictedAngleEvent predict_angle_event(const ShaftMotion& motion, std::span<const double> event_angles, double after,
                                        double until, double passed = -std::numeric_limits<double>::infinity());

}  // namespace mechsim::cosim
