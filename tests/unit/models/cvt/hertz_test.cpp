// Hertz kernels and link curvature design against check cases CC4 and CC9 (spec cvt.md §4, §9).
#include <gtest/gtest.h>

#include <cmath>

#include "mechsim/models/cvt/hertz.h"

namespace cvt = mechsim::models::cvt;

namespace {
constexpr double kMPa = 1e6;
}

// CC4 — link curvature design: r11 = 105.1, r12 = 36.6, r22 = 25.14 mm, ±0.05 mm.
TEST(CvtHertz, CC4LinkCurvatures) {
  const cvt::CvtParams p;
  const cvt::LinkCurvatures c = cvt::design_link_curvatures(p);
  EXPECT_NEAR(c.r11 * 1e3, 105.1, 0.05);
  EXPECT_NEAR(c.r12 * 1e3, 36.6, 0.05);
  EXPECT_NEAR(c.r22 * 1e3, 25.14, 0.05);
  // Admissible forces [D], printed in whole newtons.
  EXPECT_NEAR(cvt::admissible_force_disc(p), 8294.0, 0.5);
  EXPECT_NEAR(cvt::admissible_force_ring(p), 7775.0, 0.5);
  EXPECT_NEAR(cvt::admissible_force_support(p), 30600.0, 0.5);
}

// CC9 (a): b̃ = 0.2 → c_HZ,max = 0.415 at z/b = 0.856 [T], ±0.001.
TEST(CvtHertz, CC9aRockingEdgeKernel) {
  double zeta = 0.0;
  const double c = cvt::c_hz_max(0.2, &zeta);
  EXPECT_NEAR(c, 0.415, 0.001);
  EXPECT_NEAR(zeta / 0.2, 0.856, 0.001);
}

// CC9 (b): plain line contact τ_max/σ_HZ = 0.300 at z/b = 0.785 [T], ±0.002.
TEST(CvtHertz, CC9bLineContactShear) {
  double best = 0.0, at = 0.0;
  for (double x = 0.0; x <= 3.0; x += 1e-5) {
    const double v = cvt::shear_ratio_line(x);
    if (v > best) {
      best = v;
      at = x;
    }
  }
  EXPECT_NEAR(best, 0.300, 0.002);
  EXPECT_NEAR(at, 0.785, 0.002);
}

// CC9 (c): rig link at F_N = 1000 N [D], ±0.1 %.
TEST(CvtHertz, CC9cRigStressesAt1000N) {
  const cvt::CvtParams p;
  const cvt::LinkCurvatures c = cvt::design_link_curvatures(p);
  EXPECT_NEAR(cvt::sigma_link_disc(1000.0, 55.2028e-3, p, c) / kMPa, 881.6, 0.881);
  EXPECT_NEAR(cvt::sigma_link_ring(1000.0, p, c) / kMPa, 645.5, 0.645);
  const cvt::RockingEdgeStress e = cvt::sigma_link_link(1000.0, p);
  EXPECT_NEAR(e.sigma_eq / kMPa, 1246.7, 1.246);
  EXPECT_NEAR(e.sigma_line / kMPa, 1180.9, 1.180);
  EXPECT_NEAR(cvt::sigma_support(1000.0, p) / kMPa, 58.8, 0.0588);
}

// CC9 (d): Horowitz, e = 1.8182 → ω = 2.5192, μ_ω = 1.2122, ν_ω = 0.6656 (4 decimals);
// the actual contact at r_D = 55.2028 mm has ω = 105.10/42.457 = 2.4755 [D].
TEST(CvtHertz, CC9dHorowitz) {
  const double om = cvt::horowitz_omega(4.0 / 2.2);
  EXPECT_NEAR(om, 2.5192, 0.00005);
  const cvt::HorowitzCoefficients h = cvt::horowitz_coefficients(om);
  EXPECT_NEAR(h.mu, 1.2122, 0.00005);
  EXPECT_NEAR(h.nu, 0.6656, 0.00005);
  const cvt::CvtParams p;
  const cvt::LinkCurvatures c = cvt::design_link_curvatures(p);
  const double rD2 = -55.2028e-3 / std::sin(p.beta_D);
  const double RR2 = c.r12 * rD2 / (c.r12 + rD2);
  EXPECT_NEAR(RR2 * 1e3, 42.457, 0.0005);
  EXPECT_NEAR(c.r11 / RR2, 2.4755, 0.00005);
}
