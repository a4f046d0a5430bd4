#include "mechsim/models/follower/kinetostatics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mechsim/models/constants.h"

namespace mechsim::models::follower {

namespace {
constexpr double angle_tolerance = 1e-9;  // intervals built from degrees touch up to rounding
}  // namespace

void validate(const FollowerParams& params) {
  if (!(params.mass >= 0.0)) throw std::invalid_argument("follower: mass must be >= 0");
  if (!(params.spring.stiffness_n_per_m >= 0.0))
    throw std::invalid_argument("follower: spring stiffness must be >= 0");
  std::vector<FunctionalLoad> sorted = params.loads;
  std::sort(sorted.begin(), sorted.end(),
            [](const FunctionalLoad& a, const FunctionalLoad& b) { return a.start_rad < b.start_rad; });
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const FunctionalLoad& l = sorted[i];
    if (!(l.start_rad >= -angle_tolerance && l.end_rad <= two_pi + angle_tolerance &&
          l.end_rad > l.start_rad))
      throw std::invalid_argument("follower: functional load interval [" +
                                  std::to_string(l.start_rad * 180.0 / std::numbers::pi) + ", " +
                                  std::to_string(l.end_rad * 180.0 / std::numbers::pi) +
                                  ") deg must satisfy 0 <= start < end <= 360");
    if (i > 0 && l.start_rad < sorted[i - 1].end_rad - angle_tolerance)
      throw std::invalid_argument("follower: functional load intervals overlap");
  }
}

double angle_in_revolution(double theta_rad) {
  double theta = std::fmod(theta_rad, two_pi);
  if (theta < 0.0) theta += two_pi;
  if (theta >= two_pi) theta = 0.0;
  return theta;
}

std::vector<double> load_boundaries(const std::vector<FunctionalLoad>& loads) {
  std::vector<double> at;
  for (const FunctionalLoad& l : loads)
    for (double b : {l.start_rad, l.end_rad}) at.push_back(b >= two_pi ? b - two_pi : b);
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  return at;
}

bool angle_at_or_past(double theta_rad, double boundary_rad) {
  double past = angle_in_revolution(theta_rad) - boundary_rad;
  if (past < 0.0) past += two_pi;
  return past < std::numbers::pi;
}

double functional_load(const std::vector<FunctionalLoad>& loads, double theta_rad) {
  const double theta = angle_in_revolution(theta_rad);
  double total = 0.0;
  for (const FunctionalLoad& l : loads)
    if (theta >= l.start_rad && theta < l.end_rad) total += l.at(theta);
  return total;
}

FollowerForces kinetostatic_forces(const FollowerParams& params, double theta_rad, double lift_m,
                                   double lift_d1, double lift_d2, double pressure_angle_rad,
                                   double speed_rad_s, double acceleration_rad_s2) {
  FollowerForces f{};
  f.functional_load_n = functional_load(params.loads, theta_rad);
  f.spring_force_n = params.spring.preload_n + params.spring.stiffness_n_per_m * lift_m;
  f.inertia_force_n =
      params.mass * (lift_d2 * speed_rad_s * speed_rad_s + lift_d1 * acceleration_rad_s2);
  f.normal_component_n = f.functional_load_n + f.spring_force_n + f.inertia_force_n;
  f.contact_force_n = f.normal_component_n / std::cos(pressure_angle_rad);
  f.drive_torque_nm = f.normal_component_n * lift_d1;
  // The same operations as above without the S' ω̇ term: at ω̇ = 0 both are bit-identical
  // (adding an exact zero changes no double).
  const double inertia_rest = params.mass * (lift_d2 * speed_rad_s * speed_rad_s);
  f.drive_torque_rest_nm = (f.functional_load_n + f.spring_force_n + inertia_rest) * lift_d1;
  return f;
}

double reflected_inertia(double mass_kg, double lift_d1) { return mass_kg * lift_d1 * lift_d1; }

}  // namespace mechsim::models::follower
