#include "mechsim/models/cam/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mechsim/models/cam/press_cam.h"

namespace mechsim::models::cam {
namespace {

// Sampling resolution of the α(θ) scans: 0.01°. Near a smooth extremum the sampled
// value is off by ≈ |α''| h²/2 < 1e-6°, negligible; the angle of the extremum is off by at
// most half a step.
constexpr double scan_step_deg = 0.01;

struct Extreme {
  double value, angle_deg;
};

template <typename F>
std::pair<Extreme, Extreme> scan(F f, double from_deg, double to_deg) {
  Extreme lo{HUGE_VAL, 0}, hi{-HUGE_VAL, 0};
  const int n = static_cast<int>(std::lround((to_deg - from_deg) / scan_step_deg));
  for (int i = 0; i <= n; ++i) {
    const double deg = from_deg + i * scan_step_deg;
    const double v = f(deg);
    if (v < lo.value) lo = {v, deg};
    if (v > hi.value) hi = {v, deg};
  }
  return {lo, hi};
}

TEST(CamGeometry, PressCamPressureAngleExtremes) {
  const PressCam cam;
  const MotionLaw law = cam.law();
  auto alpha_deg = [&](double deg) {
    const LawPoint p = law.evaluate(deg_to_rad(deg));
    return rad_to_deg(pressure_angle(p.s, p.s_d1, cam.pitch_radius_m, 0.0));
  };
  const auto [lo, hi] = scan(alpha_deg, 0.0, 360.0);
  // The spec quotes 2 decimals: ±0.005° rounding; 0.01° tolerance.
  EXPECT_NEAR(hi.value, 23.63, 0.01);
  EXPECT_NEAR(lo.value, -28.09, 0.01);
  // Angles quoted to 0.1° (±0.05°) plus half the scan step.
  EXPECT_NEAR(hi.angle_deg, 44.5, 0.05 + scan_step_deg / 2);
  EXPECT_NEAR(lo.angle_deg, 177.3, 0.05 + scan_step_deg / 2);
}

TEST(CamGeometry, PressCamMinimumPitchCurvatureRadiusPerSegment) {
  const PressCam cam;
  const MotionLaw law = cam.law();
  auto rho_mm = [&](double deg) {
    const LawPoint p = law.evaluate(deg_to_rad(deg));
    const double rho = pitch_curvature_radius(p.s, p.s_d1, p.s_d2, cam.pitch_radius_m, 0.0);
    // The spec's per-segment figure is the smallest positive (convex) radius: concave
    // stretches (ρ < 0) are left out of this minimum.
    return rho > 0.0 ? 1e3 * rho : HUGE_VAL;
  };
  // Segment ends are included (S, S', S'' are continuous there). The minimum is either at
  // an end (exact) or smooth inside, where 0.01° sampling is off by < 1e-5 mm.
  // The spec quotes 2 decimals: 0.01 mm.
  EXPECT_NEAR(scan(rho_mm, 26.25, 45.0).first.value, 65.0, 0.01);
  EXPECT_NEAR(scan(rho_mm, 45.0, 120.0).first.value, 59.62, 0.01);
  EXPECT_NEAR(scan(rho_mm, 140.0, 210.0).first.value, 41.15, 0.01);
}

TEST(CamGeometry, DwellGivesACircle) {
  // In a dwell at lift S the pitch curve is a circle of radius √(D² + e²) about the cam
  // centre; exact up to rounding.
  const double r0 = 0.065, e = -0.0035, s = 0.01;
  const double d = std::sqrt(r0 * r0 - e * e) + s;
  EXPECT_NEAR(pitch_curvature_radius(s, 0.0, 0.0, r0, e), std::hypot(d, e), 1e-15);
  const Point2 p = pitch_contour_point(1.234, s, r0, e);
  EXPECT_NEAR(std::hypot(p.x, p.y), std::hypot(d, e), 1e-15);
  EXPECT_NEAR(pressure_angle(0.0, 0.0, r0, 0.0), 0.0, 1e-15);
}

// The signed ρ_p formula and the contour functions must describe the same curve: the
// curvature of the sampled pitch curve (central differences) equals 1/ρ_p, and the real
// contour lies at Rr from the pitch point along the normal. Checked with an eccentricity
// to pin its sign convention and the sense of rotation.
TEST(CamGeometry, ContourAgreesWithCurvatureAndPressureAngle) {
  const PressCam cam;
  const MotionLaw law = cam.law();
  const double rr = cam.roller_radius_m;
  for (double e : {-0.0035, 0.0, 0.012}) {
    for (double deg = 27.0; deg < 360.0; deg += 7.3) {
      SCOPED_TRACE("e = " + std::to_string(e) + ", theta = " + std::to_string(deg));
      const double th = deg_to_rad(deg), h = 1e-4;
      auto pitch = [&](double t) { return pitch_contour_point(t, law.evaluate(t).s, cam.pitch_radius_m, e); };
      const Point2 m = pitch(th - h), c = pitch(th), p = pitch(th + h);
      const double dx = (p.x - m.x) / (2 * h), dy = (p.y - m.y) / (2 * h);
      const double ddx = (p.x - 2 * c.x + m.x) / (h * h), ddy = (p.y - 2 * c.y + m.y) / (h * h);
      // θ turns the cam counter-clockwise, so the pitch point runs clockwise over the cam:
      // a convex curve has negative signed curvature in this parametrisation.
      const double curvature = -(dx * ddy - dy * ddx) / std::pow(dx * dx + dy * dy, 1.5);
      const LawPoint s = law.evaluate(th);
      const double rho = pitch_curvature_radius(s.s, s.s_d1, s.s_d2, cam.pitch_radius_m, e);
      // Differences with h = 1e-4 rad: truncation ≈ h² · (derivatives of order 4 of a curve
      // of size 0.1 m with S'''' ≲ 5 m/rad⁴) ≈ 1e-7 relative to |x''| ≈ 0.1; rounding
      // 1e-17/h² ≈ 1e-9. 1e-5 relative on the curvature (≈ 20 1/m) covers both.
      EXPECT_NEAR(curvature, 1.0 / rho, 1e-5 * 30.0);
      const Point2 k = cam_contour_point(th, s.s, s.s_d1, cam.pitch_radius_m, e, rr);
      EXPECT_NEAR(std::hypot(k.x - c.x, k.y - c.y), rr, 1e-15);
      // Contact normal ⟂ pitch tangent (the tangent has relative error ≈ 1e-8).
      EXPECT_NEAR(((k.x - c.x) * dx + (k.y - c.y) * dy) / (rr * std::hypot(dx, dy)), 0.0, 1e-7);
      // The normal points from the pitch point to the cam side (towards the centre).
      EXPECT_LT(std::hypot(k.x, k.y), std::hypot(c.x, c.y));
    }
  }
}

TEST(CamGeometry, NegativeEccentricityShiftsPressureAngleUp) {
  EXPECT_GT(pressure_angle(0.01, 0.02, 0.065, -0.0035), pressure_angle(0.01, 0.02, 0.065, 0.0));
  EXPECT_THROW(pressure_angle(0.0, 0.0, 0.065, 0.07), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::cam
