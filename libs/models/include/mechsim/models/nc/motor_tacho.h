// Motor–tachometer combination (spec nc_slide.md §1): a disc-armature DC motor and a
// tachometer on one flexible shaft. Linear model, states x = [i_a, ω1, ω2, θ = φ1 − φ2]:
//
//   L_a di_a/dt = U_a − R_a i_a − c ω1
//   I1 dω1/dt   = c i_a − b1 ω1 − b3 (ω1 − ω2) − k θ − T_load
//   I2 dω2/dt   = k θ + b3 (ω1 − ω2) − b2 ω2
//   dθ/dt       = ω1 − ω2                         output U_T = α ω2
//
// U_T/U_a = (m1 s + m0)/(n4 s⁴ + n3 s³ + n2 s² + n1 s + n0), coefficients derived from
// these equations (the report's appendix misprints n0 and n1). Analyses only; the
// time-domain block is motor_tacho_block.h.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <complex>

namespace mechsim::models::nc {

// Defaults: the identified set of the spec's table (DC gain 0.248, corner 17 Hz, 455 Hz).
struct MotorTachoParams {
  double armature_resistance = 0.27921;     // R_a [Ω]
  double armature_inductance = 6.62487e-5;  // L_a [H]
  double torque_constant = 0.2;             // c [N m/A] = back-emf constant [V s/rad]
  double tacho_constant = 0.0496;           // α [V s/rad]
  double motor_inertia = 1.2e-3;            // I1, rotor [kg m²]
  double tacho_inertia = 1.79214e-4;        // I2 [kg m²]
  double shaft_stiffness = 1272.23;         // k [N m/rad]
  double motor_damping = 0.0;               // b1 [N m s/rad]
  double tacho_damping = 0.0;               // b2 [N m s/rad]
  double shaft_damping = 1e-2;              // b3 [N m s/rad]
};

// The same motor with a load inertia (for example the coupling and spindle) added to I1.
MotorTachoParams with_load_inertia(MotorTachoParams params, double load_inertia);

// dx/dt = A x + B [U_a, T_load]ᵀ,  U_T = C x + D [U_a, T_load]ᵀ.
struct MotorTachoStateSpace {
  Eigen::Matrix4d a;
  Eigen::Matrix<double, 4, 2> b;
  Eigen::Matrix<double, 1, 4> c;
  Eigen::Matrix<double, 1, 2> d;
};
MotorTachoStateSpace state_space(const MotorTachoParams& p);

struct TransferFunction {
  double m1, m0;              // numerator  m1 s + m0
  double n4, n3, n2, n1, n0;  // denominator
  std::complex<double> operator()(std::complex<double> s) const;
};
// U_T/U_a from the spec's formulas.
TransferFunction tacho_transfer_function(const MotorTachoParams& p);

// Eigenvalues of A [1/s], sorted by ascending magnitude: slow mechanical pole, the shaft
// resonance pair (Im < 0 first), electrical pole — for the default set.
std::array<std::complex<double>, 4> poles(const MotorTachoParams& p);

double dc_gain(const MotorTachoParams& p);  // m0/n0 = α/c [V/V]

struct FrequencyPoint {
  double magnitude_db;  // 20 log10 |G|
  double phase_deg;     // continuous (unwrapped): arg(numerator) − Σ arg(jω − p_i)
};
FrequencyPoint frequency_response(const MotorTachoParams& p, double frequency_hz);

// First frequency, scanning upwards from DC, where |G| falls to |G(0)|/√2 [Hz].
double corner_frequency_hz(const MotorTachoParams& p);

// The shaft resonance. Peak height = 20 log10(|G(j2πf_r)| / |G(0)|): the local maximum of
// |G| near the complex pair, measured against the low-frequency asymptote, i.e. the flat
// DC level of the first-order roll-off (not against the −20 dB/decade line at f_r). This is
// the definition that gives the spec's +1.3 dB (b3 = 1e-2), 17.5 dB (1e-4) and −17 dB (1e-1).
struct Resonance {
  double frequency_hz;        // f_r, where |G| has its local maximum
  double peak_height_db;      // see above
  double natural_frequency_hz;  // |p| / 2π of the complex pair
  double damping_ratio;       // −Re p / |p|
  bool is_local_maximum;      // false: no interior maximum near the pair; f_r = natural frequency
};
// Throws std::domain_error when the shaft mode is overdamped (no complex pole pair).
Resonance resonance(const MotorTachoParams& p);

// The report's approximations (3)–(5) [Hz]: slow pole c²/(R_a(I1+I2))/2π, electrical pole
// R_a/L_a/2π, resonance √(k(I1+I2)/(I1 I2))/2π (k inside the root; the printed (5) is wrong).
struct PoleApproximations {
  double slow_pole_hz;
  double electrical_pole_hz;
  double resonance_hz;
};
PoleApproximations pole_approximations(const MotorTachoParams& p);

}  // namespace mechsim::models::nc
