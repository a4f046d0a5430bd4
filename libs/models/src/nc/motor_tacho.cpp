#include "mechsim/models/nc/motor_tacho.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "mechsim/models/constants.h"

namespace mechsim::models::nc {

namespace {

using Complex = std::complex<double>;

Complex complex_pair_pole(const MotorTachoParams& p) {
  for (const Complex& pole : poles(p))
    if (pole.imag() > 0) return pole;
  throw std::domain_error("motor-tacho model: the shaft mode is overdamped (no complex pole pair)");
}

double magnitude(const TransferFunction& g, double omega) { return std::abs(g(Complex(0, omega))); }

}  // namespace

MotorTachoParams with_load_inertia(MotorTachoParams params, double load_inertia) {
  params.motor_inertia += load_inertia;
  return params;
}

MotorTachoStateSpace state_space(const MotorTachoParams& p) {
  const double la = p.armature_inductance, ra = p.armature_resistance, c = p.torque_constant;
  const double i1 = p.motor_inertia, i2 = p.tacho_inertia, k = p.shaft_stiffness;
  const double b1 = p.motor_damping, b2 = p.tacho_damping, b3 = p.shaft_damping;
  MotorTachoStateSpace ss;
  //        i_a        ω1               ω2              θ
  ss.a << -ra / la, -c / la,          0,              0,
          c / i1,   -(b1 + b3) / i1,  b3 / i1,        -k / i1,
          0,        b3 / i2,          -(b2 + b3) / i2, k / i2,
          0,        1,                -1,             0;
  ss.b << 1 / la, 0,
          0,      -1 / i1,
          0,      0,
          0,      0;
  ss.c << 0, 0, p.tacho_constant, 0;
  ss.d << 0, 0;
  return ss;
}

Complex TransferFunction::operator()(Complex s) const {
  return (m1 * s + m0) / ((((n4 * s + n3) * s + n2) * s + n1) * s + n0);
}

TransferFunction tacho_transfer_function(const MotorTachoParams& p) {
  const double la = p.armature_inductance, ra = p.armature_resistance, c = p.torque_constant;
  const double i1 = p.motor_inertia, i2 = p.tacho_inertia, k = p.shaft_stiffness;
  const double b1 = p.motor_damping, b2 = p.tacho_damping, b3 = p.shaft_damping;
  const double damping_sum = b1 * i2 + b2 * i1 + b3 * (i1 + i2);
  const double stiffness_sum = k * (i1 + i2) + b1 * b2 + b1 * b3 + b2 * b3;
  TransferFunction g;
  g.m1 = p.tacho_constant * b3;
  g.m0 = p.tacho_constant * k;
  g.n4 = la * i1 * i2 / c;
  g.n3 = ra * i1 * i2 / c + la / c * damping_sum;
  g.n2 = ra / c * damping_sum + c * i2 + la / c * stiffness_sum;
  g.n1 = ra / c * stiffness_sum + c * (b2 + b3) + la * k * (b1 + b2) / c;
  g.n0 = c * k + ra * k * (b1 + b2) / c;
  return g;
}

std::array<Complex, 4> poles(const MotorTachoParams& p) {
  Eigen::EigenSolver<Eigen::Matrix4d> solver(state_space(p).a, false);
  if (solver.info() != Eigen::Success) throw std::runtime_error("motor-tacho poles: eigensolver failed");
  std::array<Complex, 4> result;
  for (int i = 0; i < 4; ++i) result[i] = solver.eigenvalues()(i);
  std::sort(result.begin(), result.end(), [](Complex a, Complex b) {
    // A conjugate pair has equal magnitude up to round-off: order it by the imaginary part.
    const double scale = std::max(std::abs(a), std::abs(b));
    if (std::abs(std::abs(a) - std::abs(b)) > 1e-9 * scale) return std::abs(a) < std::abs(b);
    return a.imag() < b.imag();
  });
  return result;
}

double dc_gain(const MotorTachoParams& p) {
  const TransferFunction g = tacho_transfer_function(p);
  return g.m0 / g.n0;
}

FrequencyPoint frequency_response(const MotorTachoParams& p, double frequency_hz) {
  const TransferFunction g = tacho_transfer_function(p);
  const Complex jw(0, two_pi * frequency_hz);
  // Phase as a sum of factor angles so that it stays continuous through −180°.
  double phase = std::arg(Complex(g.m0, g.m1 * jw.imag())) - std::arg(Complex(g.n4, 0));
  for (const Complex& pole : poles(p)) phase -= std::arg(jw - pole);
  return {20 * std::log10(std::abs(g(jw))), phase * 180 / std::numbers::pi};
}

double corner_frequency_hz(const MotorTachoParams& p) {
  const TransferFunction g = tacho_transfer_function(p);
  const double target = std::abs(g(0.0)) / std::sqrt(2.0);
  // Scan upwards in 1 % steps from far below the slow pole, then bisect the bracket.
  double lo = std::abs(poles(p)[0]) * 1e-3, hi = lo;
  while (magnitude(g, hi) > target) {
    lo = hi;
    hi *= 1.01;
    if (hi > 1e9) throw std::domain_error("corner_frequency_hz: |G| never falls 3 dB below DC");
  }
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (magnitude(g, mid) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) / two_pi;
}

Resonance resonance(const MotorTachoParams& p) {
  const TransferFunction g = tacho_transfer_function(p);
  const Complex pair = complex_pair_pole(p);
  const double omega_n = std::abs(pair);
  const double dc = std::abs(g(0.0));
  Resonance r{omega_n / two_pi, 20 * std::log10(magnitude(g, omega_n) / dc), omega_n / two_pi,
              -pair.real() / omega_n, false};

  // Interior local maxima of |G| on a log grid over [ω_n/2, 2 ω_n]; take the one nearest ω_n.
  constexpr int points = 4001;
  std::vector<double> omega(points), mag(points);
  for (int i = 0; i < points; ++i) {
    omega[i] = omega_n * std::pow(4.0, double(i) / (points - 1) - 0.5);
    mag[i] = magnitude(g, omega[i]);
  }
  int best = -1;
  for (int i = 1; i + 1 < points; ++i)
    if (mag[i] >= mag[i - 1] && mag[i] > mag[i + 1] &&
        (best < 0 || std::abs(std::log(omega[i] / omega_n)) < std::abs(std::log(omega[best] / omega_n))))
      best = i;
  if (best < 0) return r;

  // Golden-section refinement inside the bracketing grid cells.
  const double golden = (std::sqrt(5.0) - 1) / 2;
  double a = omega[best - 1], b = omega[best + 1];
  double x1 = b - golden * (b - a), x2 = a + golden * (b - a);
  double f1 = magnitude(g, x1), f2 = magnitude(g, x2);
  while (b - a > 1e-12 * b) {
    if (f1 > f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - golden * (b - a), f1 = magnitude(g, x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + golden * (b - a), f2 = magnitude(g, x2);
    }
  }
  const double omega_r = 0.5 * (a + b);
  r.frequency_hz = omega_r / two_pi;
  r.peak_height_db = 20 * std::log10(magnitude(g, omega_r) / dc);
  r.is_local_maximum = true;
  return r;
}

PoleApproximations pole_approximations(const MotorTachoParams& p) {
  const double c = p.torque_constant, ra = p.armature_resistance;
  const double i1 = p.motor_inertia, i2 = p.tacho_inertia;
  return {c * c / (ra * (i1 + i2)) / two_pi, ra / p.armature_inductance / two_pi,
          std::sqrt(p.shaft_stiffness * (i1 + i2) / (i1 * i2)) / two_pi};
}

}  // namespace mechsim::models::nc
