// Hertz stresses of the HCVT link contacts, spec cvt.md §4 (thesis ch. 5, code FS_*).
#include "mechsim/models/cvt/hertz.h"

#include <algorithm>
#include <cmath>

#include "mechsim/models/constants.h"

namespace mechsim::models::cvt {

namespace {

// (5.2)–(5.4) with R, r the principal relative radii.
double elliptic_stress(double F_N, double R1, double R2, double E_R) {
  const double R = std::max(R1, R2), r = std::min(R1, R2);  // (5.8), (5.9)
  const HorowitzCoefficients h = horowitz_coefficients(R / r);
  const double k = std::cbrt(3.0 * F_N * r / E_R);
  return 3.0 * F_N / (2.0 * pi * (h.mu * k) * (h.nu * k));
}
}  // namespace

HorowitzCoefficients horowitz_coefficients(double omega) {
  // (5.11) for 1 <= ω < 30, (5.12) beyond (the ranges overlap in 20..30; the branches meet near 30).
  if (omega < 30.0) return {0.7937 * std::pow(omega, 11.0 / 24.0), 0.7937 * std::pow(omega, -4.0 / 21.0)};
  return {1.015 * std::pow(omega, 8.0 / 21.0), 0.7937 * std::pow(omega, -4.0 / 21.0)};
}

double horowitz_omega(double e) {
  // Inverse of e ≈ ω^{11/17} (e < 8.86) and e ≈ 1.28 ω^{4/7}.
  return e < 8.86 ? std::pow(e, 17.0 / 11.0) : std::pow(e / 1.28, 7.0 / 4.0);
}

LinkCurvatures design_link_curvatures(const CvtParams& p) {
  LinkCurvatures c;
  const double sig = p.sigma_admissible, E = p.E_R, sb = std::sin(p.beta_D);
  const double e = std::max(p.l_D / p.t_D, p.t_D / p.l_D);  // (5.21)
  const double om = horowitz_omega(e);
  const double nu3 = std::pow(horowitz_coefficients(om).nu, 3.0);
  double r11 = 0.0, r12 = 0.0;
  for (double rD : p.r_D_design) {
    if (p.l_D >= p.t_D) {  // (5.24), (5.25)
      r12 += E * rD * p.t_D * p.t_D / (4.0 * p.l_D * nu3 * pi * rD * sig + E * p.t_D * p.t_D * sb);
      r11 += E * om * p.t_D * p.t_D / (4.0 * p.l_D * nu3 * pi * sig);
    } else {  // (5.28), (5.29)
      r11 += E * p.l_D * p.l_D / (4.0 * nu3 * pi * p.t_D * sig);
      r12 += E * p.l_D * p.l_D * om * rD / (4.0 * nu3 * pi * rD * p.t_D * sig + E * p.l_D * p.l_D * om * sb);
    }
  }
  c.r11 = r11 / static_cast<double>(p.r_D_design.size());
  c.r12 = r12 / static_cast<double>(p.r_D_design.size());
  c.r22 = E * p.r_C * p.t_C / (8.0 * p.r_C * sig + E * p.t_C * std::sin(p.beta_C));  // (5.33)
  return c;
}

double sigma_link_disc(double F_N, double r_D, const CvtParams& p, const LinkCurvatures& c) {
  if (F_N <= 0.0) return 0.0;
  const double rD2 = -r_D / std::sin(p.beta_D);       // (5.17), concave
  const double RR2 = c.r12 * rD2 / (c.r12 + rD2);     // (5.19)
  return elliptic_stress(F_N, c.r11, RR2, p.E_R);     // (5.18): R_R1 = r11
}

double sigma_link_ring(double F_N, const CvtParams& p, const LinkCurvatures& c) {
  if (F_N <= 0.0) return 0.0;
  const double rC2 = -p.r_C / std::sin(p.beta_C);  // (5.30)
  const double r = c.r22 * rC2 / (c.r22 + rC2);    // (5.31)
  return std::sqrt(F_N * p.E_R / (2.0 * pi * r * p.l_C));  // (5.14)
}

double shear_ratio_line(double x) { return x - x * x / std::sqrt(1.0 + x * x); }

double c_hz(double zeta, double b) { return shear_ratio_line(zeta / b) + shear_ratio_line((1.0 - zeta) / b); }

double c_hz_max(double b, double* zeta_at) {
  // dc/dζ = [f'(ζ/b̃) − f'((1−ζ)/b̃)]/b̃ with f'(x) = 1 − (2x + x³)/(1 + x²)^{3/2}; its root in
  // [0, 0.49] (code: fzero) by bisection: positive at 0, negative at 0.49 for b̃ up to ~1.
  auto df = [](double x) { return 1.0 - (2.0 * x + x * x * x) / std::pow(1.0 + x * x, 1.5); };
  auto dc = [&](double z) { return (df(z / b) - df((1.0 - z) / b)) / b; };
  double lo = 0.0, hi = 0.49;
  if (dc(hi) > 0.0) lo = hi;  // monotone on the interval: the maximum sits at its end
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double m = 0.5 * (lo + hi);
    (dc(m) > 0.0 ? lo : hi) = m;
  }
  const double z = 0.5 * (lo + hi);
  if (zeta_at) *zeta_at = z;
  return c_hz(z, b);
}

RockingEdgeStress sigma_link_link(double F_P, const CvtParams& p) {
  RockingEdgeStress s;
  if (F_P <= 0.0) return s;
  s.sigma_line = std::sqrt(F_P * p.E_R / (pi * p.rocking_radius * p.l_E));  // (5.35), r = r_E/2
  s.b_tilde = 2.0 * s.sigma_line * p.rho() / p.E_R;                         // (5.43)
  s.c_max = c_hz_max(s.b_tilde, &s.zeta_max);
  s.sigma_eq = s.c_max * s.sigma_line / 0.3;  // (5.49)
  return s;
}

double sigma_support(double F_N, const CvtParams& p) { return std::max(F_N, 0.0) / p.A_SU; }

double admissible_force_disc(const CvtParams& p) { return pi * p.l_D * p.t_D * p.sigma_admissible / 6.0; }
double admissible_force_ring(const CvtParams& p) { return pi * p.t_C * p.l_C * p.sigma_admissible / 4.0; }
double admissible_force_support(const CvtParams& p) { return p.A_SU * p.sigma_admissible; }

}  // namespace mechsim::models::cvt
