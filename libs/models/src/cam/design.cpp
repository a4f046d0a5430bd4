#include "mechsim/models/cam/design.h"

#include <cmath>
#include <stdexcept>

namespace mechsim::models::cam {

CamDesignReport analyse_cam_design(const CamDesignInput& in) {
  const MotionLaw law(in.segments);
  follower::validate(in.follower);
  const CamGeometry& g = in.geometry;
  if (!(g.pitch_radius_m > 0.0) || !(g.roller_radius_m >= 0.0) || !(std::abs(g.eccentricity_m) < g.pitch_radius_m))
    throw std::invalid_argument("cam design: need R0 > 0, Rr >= 0 and |e| < R0");
  if (!(in.speed_rad_s > 0.0)) throw std::invalid_argument("cam design: speed must be > 0");

  CamDesignReport r{};
  r.continuity = law.continuity();
  r.pressure_angle = pressure_angle_extremes(law, g.pitch_radius_m, g.eccentricity_m);
  r.pressure_angle_within_limit =
      std::max(std::abs(r.pressure_angle.max.value), std::abs(r.pressure_angle.min.value)) < in.pressure_angle_limit_rad;
  r.curvature = curvature_analysis(law, g);
  r.optimal_eccentricity = optimal_eccentricity(law, g.pitch_radius_m);

  r.contact_force = contact_force_extremes(law, g, in.follower, in.speed_rad_s);
  follower::FollowerParams no_spring = in.follower;
  no_spring.spring = {};
  r.contact_force_without_spring = contact_force_extremes(law, g, no_spring, in.speed_rad_s);
  r.minimum_spring = minimum_spring_stiffness(law, in.follower, in.follower.spring.preload_n, in.speed_rad_s);
  r.lift_off = kinetostatic_lift_off_speed(law, in.follower);

  r.torque = drive_torque_analysis(law, in.follower, in.speed_rad_s);
  r.flywheel = flywheel_design(r.torque, in.speed_fluctuation, in.speed_rad_s, in.flywheel_density_kg_m3,
                               in.flywheel_thickness_m);

  r.events = rest_to_rest_events(law);
  if (in.critical_event >= static_cast<int>(r.events.size()))
    throw std::invalid_argument("cam design: critical_event index beyond the law's events");
  r.critical_event = in.critical_event >= 0 ? static_cast<std::size_t>(in.critical_event)
                                            : critical_event_index(r.events);
  const RestToRestEvent& e = r.events[r.critical_event];
  r.critical_event_duration_s = e.span_rad / in.speed_rad_s;
  r.follower_stiffness_n_per_m = follower_stiffness_for_lambda(in.lambda, in.follower.mass, r.critical_event_duration_s);
  r.lambda_prime = multi_rise_lambda(in.lambda, e.span_rad);
  r.single_rise = single_rise(law, e, in.lambda, in.damping_ratio, in.steps_per_period);
  r.multi_rise = multi_rise(law, r.lambda_prime, in.damping_ratio, in.multi_rise_cycles, in.steps_per_period);
  return r;
}

}  // namespace mechsim::models::cam
