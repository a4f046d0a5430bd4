#include "mechsim/cosim/angle_event_prediction.h"

#include <cmath>

#include "mechsim/models/constants.h"

namespace mechsim::cosim {

double ShaftMotion::angle_at(double t_later) const {
  const double tau = t_later - t;
  return angle + tau * (speed + 0.5 * acceleration * tau);
}

PredictedAngleEvent predict_angle_event(const ShaftMotion& motion, std::span<const double> event_angles, double after,
                                        double until, double passed) {
  PredictedAngleEvent best;
  if (!(motion.speed > 0.0) || !(until > after)) return best;
  using models::two_pi;
  const double from = std::max(motion.angle_at(after), passed);
  for (const double event : event_angles) {
    // The first event angle + 2 pi n beyond `from`.
    double target = event + two_pi * std::floor((from - event) / two_pi);
    while (target <= from) target += two_pi;
    // tau solves acceleration tau^2 / 2 + speed tau = target - angle; the root nearest zero,
    // written so that it does not cancel when the acceleration is small.
    const double c = target - motion.angle;
    const double discriminant = motion.speed * motion.speed + 2.0 * motion.acceleration * c;
    if (!(discriminant >= 0.0)) continue;  // the shaft turns back before it gets there
    const double tau = 2.0 * c / (motion.speed + std::sqrt(discriminant));
    const double t = motion.t + tau;
    if (t > after && t <= until && t < best.t) best = {t, target};
  }
  return best;
}

}  // namespace mechsim::cosim
