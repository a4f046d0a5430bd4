// Belt geometry of the HCVT (spec cvt.md §2): link angles, the belt shape with finite links
// (transition circles, z_max search at fixed filling degree), discretisation, the slip field
// of the split belt on the support surface, and a cache of shapes over s.
//
// Lengths here are dimensionless (divided by r_C, a "~" in the spec), angles in radians.
// The shape depends on s and the link geometry only, never on load or speed.
#pragma once

#include <map>
#include <vector>

#include "mechsim/models/cvt/cvt_params.h"

namespace mechsim::models::cvt {

// Link geometry in r_C units.
struct LinkGeometry {
  double t = 0.0;    // t̃ = t/r_C
  double rho = 0.0;  // r_E/t
  double tau_S = 0.0;  // closing angle [rad]
  double bv = 0.0;     // filling degree
  static LinkGeometry from(const CvtParams& p);
};

// τ(r̃) (3.8) with the code's (1−2ρ)² denominator; NaN where it is not real.
double link_angle(double r, double rho, double t);
// r̃(τ) (3.9), the inverse of (3.8).
double link_radius(double tau, double rho, double t);

struct ContactAngles {
  double D = 0.0, C = 0.0, F = 0.0;  // γ_D, γ_C, γ_F [rad]
  bool real = false;                 // false where an arcsec argument leaves [−1, 1]
};
// γ's of the belt with transition circles of radius r̃_F (spec §2.4, code FK_gamma);
// r̃_F = 0 gives the sharp-transition (2.9)–(2.11).
ContactAngles contact_angles(double s, double z, double rf);
// bv(s̃, z̃, r̃_F) (3.23)–(3.25); NaN where the geometry is not real.
double filling_degree(double s, double z, double rf, const LinkGeometry& g);

// The belt shape at one s and everything derived from it that does not depend on load.
struct BeltShape {
  double s = 0.0, z = 0.0, rf = 0.0;  // s̃, z̃_max, r̃_F
  bool closing_angle_governed = false;  // r̃_F = r̃(τ_S) (else filling-governed)
  double gamma_D = 0.0, gamma_C = 0.0, gamma_F = 0.0;
  double tau_D = 0.0, tau_C = 0.0, tau_F = 0.0;
  int n_D = 0, n_C = 0;
  double gamma_Dd = 0.0, gamma_Cd = 0.0, gamma_Fd = 0.0;  // (4.9), (4.11), (4.12)
  double theta_D = 0.0, theta_C = 0.0;                    // θ̄ (4.27)/(4.28) with τ_F as coded
  double psi = 0.0;                                       // ψ = γ_F,d − θ̄_D − θ̄_C (4.29)
  // Per disc-contact link j = 1..n_D (index j−1): the slip field of §2.2 / §3.3, normalised
  // by v_PB, and the direction cosines of the support-surface friction (multiply by μ_SU).
  std::vector<double> xi, r_su, slip;
  std::vector<double> cos_eps_D, sin_eps_D, cos_eps_C, sin_eps_C;

  double r_D() const { return 1.0 + s - z; }   // r̃_D (2.7)
  double ratio() const { return 1.0 / r_D(); }  // i_TH (2.8)
  double mean_slip() const;
};

// Slip of a point of the neutral line at angle ξ (2.12)–(2.17), normalised by v_PB.
struct SlipPoint {
  double r_su = 0.0, zeta = 0.0;
  double v_tan_C = 0.0, v_rad_C = 0.0, v_tan_D = 0.0, v_rad_D = 0.0, v_slip = 0.0;
};
SlipPoint slip_at(double xi, double s, double z);

// The shape search of §2.4 exactly as coded (FK_zrf, FK_bandvorm) and the discretisation
// (FK_discreet). Throws std::invalid_argument when no belt shape exists at this s.
BeltShape solve_belt_shape(double s_tilde, const LinkGeometry& g, int acc = 2);
// Completes a shape from s̃, z̃, r̃_F (angles, discretisation, slip field): no search.
BeltShape shape_from(double s_tilde, double z, double rf, bool closing_governed, const LinkGeometry& g);
// The same without the per-link fields (they stay empty): what a time step needs.
BeltShape shape_scalars_from(double s_tilde, double z, double rf, bool closing_governed, const LinkGeometry& g);

// Shapes over s, searched once. `exact(s)` memoises the search per s; after `tabulate`, `at(s)`
// inside the table interpolates z̃ and r̃_F linearly between tabulated searches and derives
// the rest in closed form, so that a moving ratio costs no search. Not thread-safe.
class BeltShapeCache {
 public:
  BeltShapeCache(LinkGeometry g, int acc) : g_(g), acc_(acc) {}
  const LinkGeometry& geometry() const { return g_; }
  const BeltShape& exact(double s_tilde);
  void tabulate(double s_lo, double s_hi, int points);
  bool tabulated(double s_tilde) const;
  BeltShape at(double s_tilde);  // table if tabulated there, else exact
  // The same without the per-link fields (xi, r_su, slip, eps): no allocation where
  // tabulated, for the ratio and the link counts in a time step. Outside the table: exact().
  BeltShape scalars_at(double s_tilde);

 private:
  struct Interpolated {
    double z, rf;
    bool closing_governed;
  };
  Interpolated interpolate(double s_tilde) const;  // linear in the table; requires tabulated()
  LinkGeometry g_;
  int acc_;
  std::map<double, BeltShape> exact_;
  std::vector<double> table_s_, table_z_, table_rf_;
  std::vector<bool> table_governed_;
};

// Transition-region kinematics (3.10)–(3.13), used for Table 3-1: for a given θ_D, find θ_C
// with the n+2-link packet closing on M_C; returns θ_C, φ_D, φ_C [rad].
struct TransitionKinematics {
  double theta_C = 0.0, phi_D = 0.0, phi_C = 0.0;
};
TransitionKinematics transition_kinematics(double s, double z, const LinkGeometry& g, double tau_F, int n,
                                           double theta_D);

// The continuous-belt model of chapter 2 (spec §3.1), forces per T/r.
struct ContinuousBelt {
  ContactAngles gamma;
  bool disc_limits = true;  // the disc contact slips first (α_D = 0)
  double alpha_D = 0.0, alpha_C = 0.0;
  double F_P0 = 0.0, F_P1 = 0.0, F_A = 0.0, F_N = 0.0, F_R = 0.0;  // / (T/r)
};
ContinuousBelt continuous_belt(double s, double z, double mu_D, double mu_C, double beta, int lambda);

// Smallest self-releasing cone angle (4.5), (4.7): arctan μ + arctan μ_SU.
double min_self_releasing_cone_angle(double mu, double mu_SU);

}  // namespace mechsim::models::cvt
