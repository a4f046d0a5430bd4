#include "mechsim/models/cam/flat_face.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mechsim::models::cam {
namespace {

constexpr double pi = std::numbers::pi;

TEST(FlatFace, EnergyOfTheExercise) {
  const FlatFaceAnalysis a = analyse_flat_face(flat_face_example(0.004, 2 * pi));
  // ΔE = k (h²/2 + x0 h) = 5000 (8e-6 + 1.6e-5) = 0.12 J. Gauss–Legendre on 0.5° pieces
  // of the smooth torque integrates to rounding: 1e-12 J.
  EXPECT_NEAR(a.delta_e_closed_form_j, 0.12, 1e-15);
  EXPECT_NEAR(a.delta_e_j, 0.12, 1e-12);
  EXPECT_NEAR(a.energy_swing_j, 0.12, 1e-12);
  // No external load: the mean torque vanishes (rounding of ∮ of O(0.1 N m)).
  EXPECT_NEAR(a.mean_torque_nm, 0.0, 1e-14);
  EXPECT_TRUE(a.contact_everywhere);
  EXPECT_NEAR(flat_face_flywheel_inertia(a, 2 * pi, 0.05), 0.12 / (4 * pi * pi * 0.05), 1e-12);
}

TEST(FlatFace, EnergyIndependentOfSpeedSpanAndMass) {
  // Inertia and the cycloid's shape do no net work over a stroke between rests: ΔE
  // depends on k, x0 and h only. Cases chosen with contact kept (checked).
  for (double w : {pi, 4 * pi})
    for (double beta : {pi / 2, pi})
      for (double m : {0.05, 0.2}) {
        FlatFaceParams p = flat_face_example(0.004, w);
        p.span_rad = beta, p.mass_kg = m;
        const FlatFaceAnalysis a = analyse_flat_face(p);
        ASSERT_TRUE(a.contact_everywhere);
        EXPECT_NEAR(a.delta_e_j, 0.12, 1e-12) << "w " << w << " beta " << beta << " m " << m;
      }
}

TEST(FlatFace, ContourTouchesTheFollowerFace) {
  const FlatFaceParams p = flat_face_example(0.004, 2 * pi);
  const MotionLaw law = flat_face_law(p);
  for (double deg = 3.0; deg < 360.0; deg += 11.0) {
    const double th = deg_to_rad(deg);
    const FlatFacePoint f = flat_face_point(p, th);
    const LawPoint s = law.evaluate(th);
    // Turned back by θ (the cam turns counter-clockwise), the contact point lies on the
    // face y = R_b + s at x = q = ds/dθ (geometry of the envelope; rounding 1e-17 m).
    const double c = std::cos(th), sn = std::sin(th);
    EXPECT_NEAR(c * f.contour.x - sn * f.contour.y, s.s_d1, 1e-15);
    EXPECT_NEAR(sn * f.contour.x + c * f.contour.y, p.base_radius_m + s.s, 1e-15);
    EXPECT_NEAR(f.contour_radius_m, std::hypot(p.base_radius_m + s.s, s.s_d1), 1e-15);
    // Force and torque by their definitions (a few roundings).
    EXPECT_NEAR(f.contact_force_n, 5000.0 * (s.s + 0.004) + 0.1 * s.s_d2 * 4 * pi * pi, 1e-12);
    EXPECT_NEAR(f.torque_nm, f.contact_force_n * s.s_d1, 1e-15);
    EXPECT_NEAR(f.power_w, f.torque_nm * 2 * pi, 1e-14);
  }
}

TEST(FlatFace, PeakPowerBeatsAFineScan) {
  const FlatFaceParams p = flat_face_example(0.004, 2 * pi);
  const FlatFaceAnalysis a = analyse_flat_face(p);
  double best = -HUGE_VAL;
  for (int i = 0; i < 36000; ++i) best = std::max(best, flat_face_point(p, deg_to_rad(i * 0.01)).power_w);
  // The refined maximum is not below any sample, and a 0.01° scan of a smooth peak falls
  // short by < |P''| h²/2 ≈ 1e-8 W.
  EXPECT_GE(a.peak_power_w, best - 1e-15);
  EXPECT_NEAR(a.peak_power_w, best, 1e-6);
  EXPECT_GT(a.min_curvature_radius_m, 0.0);
}

TEST(FlatFace, ContactLostAtHighSpeedAndRefusals) {
  // The return's deceleration m s'' ω² exceeds the spring force at high speed.
  FlatFaceParams p = flat_face_example(0.004, 200 * pi);
  EXPECT_FALSE(analyse_flat_face(p).contact_everywhere);
  p.span_rad = 4.0;  // 2β > 2π
  EXPECT_THROW(analyse_flat_face(p), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::cam
