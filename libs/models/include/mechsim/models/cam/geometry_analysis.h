// Design checks of the cam geometry over a whole cycle (spec cam.md §2, §7): pressure-angle
// extremes, pitch-curve curvature per piece and undercut, optimal eccentricity, and the
// sampled contour for drawing and manufacturing.
#pragma once

#include <cstddef>
#include <vector>

#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/cam/motion_law.h"

namespace mechsim::models::cam {

struct CamGeometry {
  double pitch_radius_m;   // R0
  double roller_radius_m;  // Rr
  double eccentricity_m;   // e
};

// A value and the cam angle in [0, 2π) where it occurs.
struct AngleExtremum {
  double angle_rad;
  double value;
};

struct PressureAngleExtremes {
  AngleExtremum max;  // value in rad
  AngleExtremum min;
};

// α(θ) extremes over the cycle: sampled every 0.05° and refined to ~1e-12 rad.
PressureAngleExtremes pressure_angle_extremes(const MotionLaw& law, double pitch_radius_m,
                                              double eccentricity_m);

struct PieceCurvature {
  std::size_t piece_index;  // into law.pieces()
  Segment segment;          // the piece (a dwell filling a gap when `filler`)
  bool filler;
  bool has_convex;                       // ρ_p > 0 somewhere on the piece
  double min_positive_rho_m;             // smallest ρ_p > 0 (convex), +inf without
  double angle_min_positive_rad;
  bool has_concave;                      // ρ_p < 0 somewhere
  double min_concave_abs_rho_m;          // smallest |ρ_p| where ρ_p < 0, +inf without
  double angle_min_concave_rad;
};

struct CurvatureAnalysis {
  std::vector<PieceCurvature> pieces;
  double min_positive_rho_m;      // over the cycle
  double angle_min_positive_rad;
  double min_contour_rho_m;       // ρ_c = min ρ_p − Rr on the convex parts
  bool undercut;                  // 0 < ρ_p < Rr somewhere: the roller cannot follow
};

CurvatureAnalysis curvature_analysis(const MotionLaw& law, const CamGeometry& geometry);

struct OptimalEccentricity {
  double eccentricity_m;          // minimises ||α_max| − |α_min||
  PressureAngleExtremes alpha;    // at that eccentricity
};

// Searches e in (−R0/2, R0/2): |α_max| − |α_min| decreases monotonically with e (a
// negative e shifts α up), so the optimum is its root, found to ~1e-12 m.
OptimalEccentricity optimal_eccentricity(const MotionLaw& law, double pitch_radius_m);

struct ContourSample {
  double theta_rad;
  double lift_m;
  double pressure_angle_rad;
  double pitch_rho_m;    // signed ρ_p (±inf at an inflexion)
  double contour_rho_m;  // ρ_p − Rr
  Point2 pitch;          // roller centre, cam frame
  Point2 contour;        // real cam contour, cam frame
};

// `count` equally spaced samples over [0, 2π) (θ_i = 2π i/count) for export and plots.
std::vector<ContourSample> sample_contour(const MotionLaw& law, const CamGeometry& geometry, int count);

}  // namespace mechsim::models::cam
