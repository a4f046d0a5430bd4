// Hertz stresses of the four link contacts (spec cvt.md §4, thesis ch. 5). The formulas are
// dimensionally homogeneous: SI in, SI out (N, m, Pa).
#pragma once

#include "mechsim/models/cvt/cvt_params.h"

namespace mechsim::models::cvt {

// Horowitz approximation of the elliptic-contact coefficients (5.11)/(5.12).
struct HorowitzCoefficients {
  double mu = 0.0, nu = 0.0;
};
HorowitzCoefficients horowitz_coefficients(double omega);  // FS_puntmunu
double horowitz_omega(double e);                           // FS_om: ω from the ellipse ratio e

// Link face curvatures designed so that the contact just fills the face at σ̄_HZ.
struct LinkCurvatures {
  double r11 = 0.0, r12 = 0.0;  // disc face, means over the design r_D (5.24)/(5.25) or (5.28)/(5.29) [m]
  double r22 = 0.0;             // C face (5.33) [m]
};
LinkCurvatures design_link_curvatures(const CvtParams& p);

// Contact 1, link–disc (elliptic), at disc-contact radius r_D (5.17)–(5.19), (5.2)–(5.4).
double sigma_link_disc(double F_N, double r_D, const CvtParams& p, const LinkCurvatures& c);
// Contact 2, link–C cone (line) (5.30), (5.31), (5.14).
double sigma_link_ring(double F_N, const CvtParams& p, const LinkCurvatures& c);
// Contact 3, link–link rocking edge loaded on both faces (5.35)–(5.49).
struct RockingEdgeStress {
  double sigma_line = 0.0;  // plain line-contact σ_HZ (5.35) [Pa]
  double b_tilde = 0.0;     // b/t (5.43)
  double c_max = 0.0;       // c_HZ,max (5.48)
  double zeta_max = 0.0;    // ζ = z/t of the maximum
  double sigma_eq = 0.0;    // σ_HZ,eq = c_HZ,max σ_HZ / 0.3 (5.49): the reported σ3 [Pa]
};
RockingEdgeStress sigma_link_link(double F_P, const CvtParams& p);
// c_HZ(ζ; b̃) (5.46) corrected: two (5.16) curves, one from each face; and its maximum.
double shear_ratio_line(double z_over_b);  // (5.16) τ/σ_HZ
double c_hz(double zeta, double b_tilde);
double c_hz_max(double b_tilde, double* zeta_at = nullptr);
// Contact 4, link–support surface (flat) (5.53).
double sigma_support(double F_N, const CvtParams& p);
// Admissible normal forces at σ̄_HZ: contact 1 (5.20), 2 (5.34), 4 (5.54) [N].
double admissible_force_disc(const CvtParams& p);
double admissible_force_ring(const CvtParams& p);
double admissible_force_support(const CvtParams& p);

}  // namespace mechsim::models::cvt
