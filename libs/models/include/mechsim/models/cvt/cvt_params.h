// Parameters of the HCVT push-belt CVT (spec cvt.md §6.1, the thesis's simulated test rig).
// SI units here; the model converts to the thesis's mm / N / N/mm² internally so that its
// equations can be checked line by line against the spec.
#pragma once

#include <array>
#include <compare>
#include <numbers>

namespace mechsim::models::cvt {

inline constexpr double kDeg = std::numbers::pi / 180.0;

// One tapered roller bearing (Table B2-1).
struct TaperedBearing {
  double mean_diameter = 0.0;  // d_m = (d + D)/2 [m]
  double axial_factor = 0.0;   // Y [-]
  double pressure_centre = 0.0;  // a [m] (a1 for bearing A, a2 for bearing B)
  auto operator<=>(const TaperedBearing&) const = default;
};

// The two bearings of one shaft in O arrangement and their spacing (spec §3.9).
struct ShaftBearings {
  TaperedBearing A, B;
  double l1 = 0.0;  // [m]
  double l2 = 0.0;  // [m]
  auto operator<=>(const ShaftBearings&) const = default;
};

struct CvtParams {
  int lambda = 1;              // flanks per link: 1 split belt, 2 Λ belt
  bool disc_driving = false;   // rig: the intermediate body C drives (Cdriv = 1)
  // belt and link
  double r_C = 41.5e-3;        // neutral-line radius in C [m]
  double link_thickness = 2.4e-3;   // t [m]
  double rocking_radius = 7.5e-3;   // r_E [m]
  double closing_angle = 5.6 * kDeg;  // τ_S [rad]
  double filling_degree = 0.997;    // bv [-]
  double link_mass = 1.4e-3;        // M [kg]
  // cones
  double beta_D = 12.0 * kDeg;
  double beta_C = 28.0 * kDeg;
  // friction
  double mu_D = 0.12, mu_C = 0.12, mu_E = 0.12;
  double mu_SUC = 0.10;  // support surface while in C contact
  double mu_SU = 0.06;   // support surface while in disc contact (macroslip)
  // contact faces and material
  double sigma_admissible = 1800e6;  // σ̄_HZ [Pa]
  double E_R = 2.3e11;               // reduced modulus 2E* [Pa]
  double t_D = 2.2e-3, l_D = 4.0e-3;  // disc face [m]
  double t_C = 2.2e-3, l_C = 2.5e-3;  // C face [m]
  double l_E = 7.0e-3;               // rocking-edge length [m]
  double A_SU = 17e-6;               // support face [m²]
  std::array<double, 2> r_D_design{45e-3, 95e-3};  // r_D range for the r11/r12 design [m]
  // bearings (Table B2-1) and grease base-oil viscosity
  ShaftBearings primary{{48.5e-3, 1.3, 15e-3}, {57.5e-3, 1.7, 18e-3}, 53e-3, 67e-3};
  ShaftBearings secondary{{53.5e-3, 1.6, 15e-3}, {57.5e-3, 1.7, 18e-3}, 53e-3, 70e-3};
  double grease_viscosity = 30e-6;  // ν [m²/s]
  // numerics / fidelity (reference values reproduce the thesis, spec §8.1)
  int acc = 2;                     // belt-shape search resolution 1..3
  double duwproc = 0.05;           // F_P0 step / (T/r)
  bool full_angle = true;          // ξ = θ, τ as coded (false: text Table 4-2, θ/2, τ/2)
  bool quirk_muSUC_radial = true;  // (4.65) 3rd term with the radial component, as coded
  bool quirk_last_sweep_FA = true;   // (4.65) 3rd term with F_A of the last sweep run, as coded
  bool round_clamping_force = true;  // F_K rounded to whole newtons (as coded; feeds the bearings)
  // range in which the thesis's model was exercised (outside: computed but flagged)
  double s_min = 5e-3, s_max = 55e-3;                 // [m]
  double torque_min = 20.0, torque_max = 120.0;       // T_C [Nm]
  double speed_min = 1000.0 * std::numbers::pi / 30.0;  // ω_C [rad/s]
  double speed_max = 5000.0 * std::numbers::pi / 30.0;

  double rho() const { return rocking_radius / link_thickness; }
  // Member by member (a process-wide cache of belt tables is keyed on the parameters).
  auto operator<=>(const CvtParams&) const = default;
};

}  // namespace mechsim::models::cvt
