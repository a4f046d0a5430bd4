// Geometry of a disc cam with a translating roller follower (spec cam.md §2).
//
// Frame: the cam centre is the origin, the follower axis is the line x = e (eccentricity
// e), the follower translates along +y. The cam turns counter-clockwise (the positive
// sense) through θ, so that tan α = (S' − e)/(√(R0² − e²) + S) with α > 0 when the
// contact normal leans towards −x. Contours are given in the cam-fixed frame, which
// coincides with the fixed frame at θ = 0.
#pragma once

namespace mechsim::models::cam {

// D = √(R0² − e²) + S: the height of the roller centre above the cam centre. Throws
// std::invalid_argument when |e| ≥ R0.
double roller_centre_height(double lift_m, double pitch_radius_m, double eccentricity_m);

// Pressure angle α in rad: tan α = (S' − e)/D.
double pressure_angle(double lift_m, double lift_d1, double pitch_radius_m, double eccentricity_m);

// Signed radius of curvature of the pitch curve (> 0 convex, < 0 concave):
// ρ_p = (D² + (S' − e)²)^1.5 / (D(D − S'') + (S' − e)(2S' − e)). Infinite (±HUGE_VAL)
// where the denominator vanishes (an inflexion of the pitch curve).
double pitch_curvature_radius(double lift_m, double lift_d1, double lift_d2, double pitch_radius_m,
                              double eccentricity_m);

// Signed curvature 1/ρ_p of the pitch curve (1/m): smooth where ρ_p passes through
// infinity, so extremum searches work on it rather than on ρ_p.
double pitch_curvature(double lift_m, double lift_d1, double lift_d2, double pitch_radius_m,
                       double eccentricity_m);

struct Point2 {
  double x, y;
};

// Roller centre (pitch curve) in the cam-fixed frame at cam angle θ.
Point2 pitch_contour_point(double theta_rad, double lift_m, double pitch_radius_m,
                           double eccentricity_m);
// Contact point on the real cam contour: the pitch point moved by the roller radius Rr
// along the contact normal towards the cam (valid while there is no undercut).
Point2 cam_contour_point(double theta_rad, double lift_m, double lift_d1, double pitch_radius_m,
                         double eccentricity_m, double roller_radius_m);

}  // namespace mechsim::models::cam
