// Disc cam with a translating flat-faced follower (spec cam.md §6, "the exercise"):
// cycloidal rise of h over β followed by a cycloidal return over the next β, dwell after.
// The contact point is offset from the follower axis by q = ds/dθ; contact force with a
// preloaded spring and inertia, no external load: F_c = k (s + x0) + m s̈ (constant speed).
#pragma once

#include <vector>

#include "mechsim/models/cam/geometry.h"
#include "mechsim/models/cam/motion_law.h"

namespace mechsim::models::cam {

struct FlatFaceParams {
  double base_radius_m;      // R_b
  double lift_m;             // h
  double span_rad;           // β (rise over [0, β], return over [β, 2β]; 2β ≤ 2π)
  double speed_rad_s;        // ω
  double mass_kg;            // m
  double spring_stiffness_n_per_m;  // k
  double spring_preload_n;   // k x0
};

// The exercise's numbers: m = 0.1 kg, k = 5000 N/m, k x0 = 20 N, R_b = 40 mm, β = π; h and
// ω are the caller's (h = 4 mm gives ΔE = 0.12 J).
FlatFaceParams flat_face_example(double lift_m, double speed_rad_s);

// The rise/return law as a MotionLaw (two full cycloids).
MotionLaw flat_face_law(const FlatFaceParams& params);

struct FlatFacePoint {
  double theta_rad;
  double lift_m;          // s
  double offset_m;        // q = ds/dθ: contact point offset from the follower axis
  double acceleration;    // s̈ = s'' ω², m/s²
  double contour_radius_m;  // r_c = √((R_b + s)² + q²)
  double contour_angle_rad; // ψ_c = θ + atan(q/(R_b + s)), measured as θ (the exercise)
  Point2 contour;         // the same point in the cam frame of geometry.h (x = r sin ψ, y = r cos ψ)
  double curvature_radius_m;  // R_b + s + s'': must stay > 0 (no cusp)
  double contact_force_n;     // F_c = k (s + x0) + m s̈
  double torque_nm;           // M = F_c q
  double power_w;             // F_c ṡ = M ω
};

FlatFacePoint flat_face_point(const FlatFaceParams& params, double theta_rad);

struct FlatFaceAnalysis {
  double mean_torque_nm;        // 0 up to quadrature error (no external load)
  double delta_e_j;             // positive area of M − M_mean over the cycle
  double energy_swing_j;        // max − min of ∫(M − M_mean) dθ (equals ΔE with one lobe each way)
  double delta_e_closed_form_j; // k (h²/2 + x0 h)
  double peak_power_w, angle_peak_power_rad;  // motor sizing
  double min_contact_force_n, angle_min_contact_force_rad;
  bool contact_everywhere;      // F_c > 0
  double min_curvature_radius_m;
  double max_offset_m;          // max |q|: the follower face must be wider than 2 max q
};

FlatFaceAnalysis analyse_flat_face(const FlatFaceParams& params);

// I = ΔE/(ω² c_s) for a speed fluctuation coefficient c_s.
double flat_face_flywheel_inertia(const FlatFaceAnalysis& analysis, double speed_rad_s,
                                  double speed_fluctuation);

}  // namespace mechsim::models::cam
