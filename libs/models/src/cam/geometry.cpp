#include "mechsim/models/cam/geometry.h"

#include <cmath>
#include <stdexcept>

namespace mechsim::models::cam {

namespace {
// The fixed-frame point p seen from the cam frame after a counter-clockwise turn θ.
Point2 to_cam_frame(double theta, double x, double y) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * x + s * y, -s * x + c * y};
}
}  // namespace

double roller_centre_height(double lift_m, double pitch_radius_m, double eccentricity_m) {
  if (!(std::abs(eccentricity_m) < pitch_radius_m))
    throw std::invalid_argument("cam geometry: |eccentricity| must be smaller than the pitch radius");
  return std::sqrt(pitch_radius_m * pitch_radius_m - eccentricity_m * eccentricity_m) + lift_m;
}

double pressure_angle(double lift_m, double lift_d1, double pitch_radius_m, double eccentricity_m) {
  const double d = roller_centre_height(lift_m, pitch_radius_m, eccentricity_m);
  return std::atan((lift_d1 - eccentricity_m) / d);
}

double pitch_curvature_radius(double lift_m, double lift_d1, double lift_d2, double pitch_radius_m,
                              double eccentricity_m) {
  const double kappa = pitch_curvature(lift_m, lift_d1, lift_d2, pitch_radius_m, eccentricity_m);
  return kappa == 0.0 ? HUGE_VAL : 1.0 / kappa;
}

double pitch_curvature(double lift_m, double lift_d1, double lift_d2, double pitch_radius_m,
                       double eccentricity_m) {
  const double d = roller_centre_height(lift_m, pitch_radius_m, eccentricity_m);
  const double q = lift_d1 - eccentricity_m;
  return (d * (d - lift_d2) + q * (2.0 * lift_d1 - eccentricity_m)) / std::pow(d * d + q * q, 1.5);
}

Point2 pitch_contour_point(double theta_rad, double lift_m, double pitch_radius_m,
                           double eccentricity_m) {
  const double d = roller_centre_height(lift_m, pitch_radius_m, eccentricity_m);
  return to_cam_frame(theta_rad, eccentricity_m, d);
}

Point2 cam_contour_point(double theta_rad, double lift_m, double lift_d1, double pitch_radius_m,
                         double eccentricity_m, double roller_radius_m) {
  const double d = roller_centre_height(lift_m, pitch_radius_m, eccentricity_m);
  const double alpha = std::atan((lift_d1 - eccentricity_m) / d);
  // Unit contact normal (from the cam towards the roller) is (−sin α, cos α).
  return to_cam_frame(theta_rad, eccentricity_m + roller_radius_m * std::sin(alpha),
                      d - roller_radius_m * std::cos(alpha));
}

}  // namespace mechsim::models::cam
