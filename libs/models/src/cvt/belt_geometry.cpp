// Belt geometry of the HCVT, spec cvt.md §2 (equation numbers are the thesis's).
#include "mechsim/models/cvt/belt_geometry.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include "mechsim/models/constants.h"

namespace mechsim::models::cvt {

namespace {

using cplx = std::complex<double>;

// acos as MATLAB evaluates it: real arguments outside [−1, 1] give 0 + i·acosh(x) or
// π − i·acosh(−x). The belt-shape search keeps a point only while bv is real and stops on
// Re(bv), so the real parts must follow MATLAB's branches.
cplx acos_m(cplx x) {
  if (x.imag() == 0.0) {
    const double r = x.real();
    if (r > 1.0) return {0.0, std::acosh(r)};
    if (r < -1.0) return {pi, -std::acosh(-r)};
    return {std::acos(r), 0.0};
  }
  return std::acos(x);
}

cplx sqrt_m(double x) { return x >= 0.0 ? cplx{std::sqrt(x), 0.0} : cplx{0.0, std::sqrt(-x)}; }

cplx link_angle_c(double r, double rho, double t) {
  const cplx root = sqrt_m(r * r * (4.0 * r * r + (1.0 - 4.0 * rho) * t * t));
  const double den = 4.0 * r * r + (1.0 - 2.0 * rho) * (1.0 - 2.0 * rho) * t * t;
  return 2.0 * acos_m(2.0 * (rho * (2.0 * rho - 1.0) * t * t + root) / den);
}

struct AnglesC {
  cplx D, C, F;
};

AnglesC contact_angles_c(double s, double z, double rf) {
  const double G1 = 2.0 * (rf - 1.0) * (rf - 1.0 - s + z) /
                    (2.0 * (rf - 1.0) * (rf - 1.0 - s) + 2.0 * (rf - 1.0 - s) * z + z * z);
  const double G2 = 2.0 * s * (1.0 - rf + s - z) /
                    (2.0 * s * s - 2.0 * s * (rf + z - 1.0) + z * (2.0 * rf + z - 2.0));
  AnglesC a;
  a.D = 2.0 * acos_m(cplx{1.0 / G2, 0.0});
  a.F = acos_m(cplx{1.0 / G1, 0.0});
  a.C = 2.0 * pi - a.D - 2.0 * a.F;
  return a;
}

cplx filling_degree_c(double s, double z, double rf, const LinkGeometry& g) {
  const AnglesC a = contact_angles_c(s, z, rf);
  const cplx tau_D = link_angle_c(1.0 + s - z, g.rho, g.t);
  const cplx tau_C = link_angle_c(1.0, g.rho, g.t);
  const cplx tau_F = link_angle_c(rf, g.rho, g.t);
  const cplx n_bv = a.D / tau_D + a.C / tau_C + 2.0 * a.F / tau_F;  // (3.24)
  return n_bv / (2.0 * pi / tau_C);                                // (3.23), (3.25)
}

// MATLAB interp1 (linear) on a monotone x; NaN outside.
double interp1(const std::vector<double>& x, const std::vector<double>& y, double xi) {
  const std::size_t n = x.size();
  if (n == 0) return nan;
  if (n == 1) return xi == x[0] ? y[0] : nan;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double a = x[k], b = x[k + 1];
    if ((xi - a) * (xi - b) <= 0.0) {
      if (a == b) return y[k];
      return y[k] + (xi - a) / (b - a) * (y[k + 1] - y[k]);
    }
  }
  return nan;
}

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = n == 1 ? a : a + (b - a) * i / (n - 1);
  if (n > 1) v.back() = b;
  return v;
}

}  // namespace

LinkGeometry LinkGeometry::from(const CvtParams& p) {
  return {p.link_thickness / p.r_C, p.rho(), p.closing_angle, p.filling_degree};
}

double link_angle(double r, double rho, double t) {
  const cplx v = link_angle_c(r, rho, t);
  return v.imag() == 0.0 ? v.real() : nan;
}

double link_radius(double tau, double rho, double t) {
  return 0.5 * t * ((1.0 - 2.0 * rho) / std::tan(tau / 2.0) + 2.0 * rho / std::sin(tau / 2.0));
}

ContactAngles contact_angles(double s, double z, double rf) {
  const AnglesC a = contact_angles_c(s, z, rf);
  ContactAngles r;
  r.real = a.D.imag() == 0.0 && a.F.imag() == 0.0;
  r.D = a.D.real();
  r.C = a.C.real();
  r.F = a.F.real();
  return r;
}

double filling_degree(double s, double z, double rf, const LinkGeometry& g) {
  const cplx bv = filling_degree_c(s, z, rf, g);
  return std::abs(bv.imag()) < 1e-12 ? bv.real() : nan;
}

double BeltShape::mean_slip() const {
  if (slip.empty()) return 0.0;
  double sum = 0.0;
  for (double v : slip) sum += v;
  return sum / static_cast<double>(slip.size());
}

SlipPoint slip_at(double xi, double s, double z) {
  SlipPoint p;
  const double rD = 1.0 + s - z;
  p.r_su = std::sqrt(rD * rD + s * s - 2.0 * rD * s * std::cos(xi));  // (2.13)
  if (std::abs(xi) > 1e-10) {                                          // code: ζ = 0 at ξ = 0
    const double c = (p.r_su * p.r_su + (z - 1.0) * (z - 1.0 - 2.0 * s)) / (2.0 * p.r_su * rD);  // (2.14) corrected
    p.zeta = std::acos(std::clamp(c, -1.0, 1.0));
  }
  p.v_tan_C = std::cos(p.zeta) - p.r_su;  // (2.15)
  p.v_rad_C = std::sin(p.zeta);
  p.v_tan_D = 1.0 - p.r_su * std::cos(p.zeta);  // (2.16)
  p.v_rad_D = p.r_su * std::sin(p.zeta);
  p.v_slip = std::hypot(p.v_tan_C, p.v_rad_C);  // (2.17)
  return p;
}

BeltShape shape_scalars_from(double s, double z, double rf, bool closing_governed, const LinkGeometry& g) {
  BeltShape b;
  b.s = s;
  b.z = z;
  b.rf = rf;
  b.closing_angle_governed = closing_governed;
  const ContactAngles a = contact_angles(s, z, rf);
  if (!a.real) throw std::invalid_argument("no real belt shape at s/r_C = " + std::to_string(s));
  b.gamma_D = a.D;
  b.gamma_C = a.C;
  b.gamma_F = a.F;
  b.tau_D = link_angle(b.r_D(), g.rho, g.t);
  b.tau_C = link_angle(1.0, g.rho, g.t);
  b.tau_F = link_angle(rf, g.rho, g.t);
  if (!std::isfinite(b.tau_D) || !std::isfinite(b.tau_C) || !std::isfinite(b.tau_F))
    throw std::invalid_argument("link angles not real at s/r_C = " + std::to_string(s));
  // Discretisation FK_discreet: (4.8)–(4.12), (4.27)–(4.28) with τ_F as coded.
  b.n_D = static_cast<int>(std::floor(b.gamma_D / b.tau_D));
  b.n_C = static_cast<int>(std::floor(b.gamma_C / b.tau_C));
  b.gamma_Dd = (b.n_D - 1) * b.tau_D;
  b.gamma_Cd = (b.n_C - 1) * b.tau_C;
  b.gamma_Fd = (2.0 * pi - b.gamma_Dd - b.gamma_Cd) / 2.0;
  b.theta_D = (b.tau_D + b.tau_F) / 2.0;
  b.theta_C = (b.tau_C + b.tau_F) / 2.0;
  b.psi = b.gamma_Fd - b.theta_D - b.theta_C;
  return b;
}

BeltShape shape_from(double s, double z, double rf, bool closing_governed, const LinkGeometry& g) {
  BeltShape b = shape_scalars_from(s, z, rf, closing_governed, g);
  // Slip field of the split belt at the disc-contact links, ξ_j = −γ_D,d/2 + (j−1)τ_D.
  for (int j = 1; j <= b.n_D; ++j) {
    const double xi = -b.gamma_Dd / 2.0 + (j - 1) * b.tau_D;
    const SlipPoint p = slip_at(xi, s, z);
    b.xi.push_back(xi);
    b.r_su.push_back(p.r_su);
    b.slip.push_back(p.v_slip);
    // FF_muSU: ε = atan(v_rad/v_tan) (4.14)–(4.20), w.r.t. M_D and M_C.
    const double eD = std::atan(p.v_rad_D / p.v_tan_D);
    const double eC = std::atan(p.v_rad_C / p.v_tan_C);
    b.cos_eps_D.push_back(std::cos(eD));
    b.sin_eps_D.push_back(std::sin(eD));
    b.cos_eps_C.push_back(std::cos(eC));
    b.sin_eps_C.push_back(std::sin(eC));
  }
  return b;
}

BeltShape solve_belt_shape(double s, const LinkGeometry& g, int acc) {
  if (!(s > 0.0) || !std::isfinite(s)) throw std::invalid_argument("belt shape: s must be > 0");
  const int n_rf = acc <= 1 ? 25 : acc == 2 ? 50 : 100;
  const double dz = acc <= 1 ? 1e-3 : acc == 2 ? 5e-4 : 1e-4;
  const int max_steps = static_cast<int>(2.0 / dz);  // z̃ ≤ 2: far beyond any belt
  // FK_zrf: z̃(r̃_F) at the target filling degree.
  std::vector<double> rf_ok, z_ok;
  for (double rf : linspace(0.001, 0.999, n_rf)) {
    std::vector<double> zs, bvs;
    double z = 0.0;
    for (int k = 0; k < max_steps; ++k) {
      z += dz;
      const cplx bv = filling_degree_c(s, z, rf, g);
      if (std::abs(bv.imag()) < 1e-12) {
        zs.push_back(z);
        bvs.push_back(bv.real());
      }
      if (bv.real() <= g.bv - 0.001) break;
    }
    if (bvs.empty()) continue;
    const auto [lo, hi] = std::minmax_element(bvs.begin(), bvs.end());
    if (g.bv < *lo || g.bv > *hi) continue;
    const double zt = interp1(bvs, zs, g.bv);
    if (std::isfinite(zt)) {
      rf_ok.push_back(rf);
      z_ok.push_back(zt);
    }
  }
  if (rf_ok.empty())
    throw std::invalid_argument("no belt shape with filling degree " + std::to_string(g.bv) + " at s/r_C = " +
                                std::to_string(s));
  // Resample on 100 points, take the maximum z̃ (optimal filling), then the τ_S rule.
  const std::vector<double> rf100 = linspace(rf_ok.front(), rf_ok.back(), 100);
  std::vector<double> z100(rf100.size());
  for (std::size_t i = 0; i < rf100.size(); ++i) z100[i] = interp1(rf_ok, z_ok, rf100[i]);
  std::size_t imax = 0;
  for (std::size_t i = 1; i < z100.size(); ++i)
    if (z100[i] > z100[imax]) imax = i;
  double rf = rf100[imax], z = z100[imax];
  bool governed = false;
  const double rf_min = link_radius(g.tau_S, g.rho, g.t);
  if (rf < rf_min) {
    rf = rf_min;
    z = interp1(rf100, z100, rf_min);
    governed = true;
    if (!std::isfinite(z))
      throw std::invalid_argument("belt shape: r_F(tau_S) outside the valid transition radii at s/r_C = " +
                                  std::to_string(s));
  }
  return shape_from(s, z, rf, governed, g);
}

const BeltShape& BeltShapeCache::exact(double s) {
  auto it = exact_.find(s);
  if (it == exact_.end()) it = exact_.emplace(s, solve_belt_shape(s, g_, acc_)).first;
  return it->second;
}

void BeltShapeCache::tabulate(double lo, double hi, int points) {
  if (points < 2 || !(hi > lo)) throw std::invalid_argument("belt-shape table: need hi > lo and >= 2 points");
  table_s_ = linspace(lo, hi, points);
  table_z_.clear();
  table_rf_.clear();
  table_governed_.clear();
  for (double s : table_s_) {
    const BeltShape& b = exact(s);
    table_z_.push_back(b.z);
    table_rf_.push_back(b.rf);
    table_governed_.push_back(b.closing_angle_governed);
  }
}

bool BeltShapeCache::tabulated(double s) const {
  return !table_s_.empty() && s >= table_s_.front() && s <= table_s_.back();
}

BeltShapeCache::Interpolated BeltShapeCache::interpolate(double s) const {
  const auto up = std::upper_bound(table_s_.begin(), table_s_.end(), s);
  std::size_t k = up == table_s_.begin() ? 0 : static_cast<std::size_t>(up - table_s_.begin()) - 1;
  if (k + 1 >= table_s_.size()) k = table_s_.size() - 2;
  const double w = (s - table_s_[k]) / (table_s_[k + 1] - table_s_[k]);
  return {table_z_[k] + w * (table_z_[k + 1] - table_z_[k]), table_rf_[k] + w * (table_rf_[k + 1] - table_rf_[k]),
          table_governed_[k] && table_governed_[k + 1]};
}

BeltShape BeltShapeCache::scalars_at(double s) {
  if (!tabulated(s)) return exact(s);
  const Interpolated i = interpolate(s);
  return shape_scalars_from(s, i.z, i.rf, i.closing_governed, g_);
}

BeltShape BeltShapeCache::at(double s) {
  if (!tabulated(s)) return exact(s);
  const Interpolated i = interpolate(s);
  return shape_from(s, i.z, i.rf, i.closing_governed, g_);
}

TransitionKinematics transition_kinematics(double s, double z, const LinkGeometry& g, double tau_F, int n,
                                           double theta_D) {
  const double rF = link_radius(tau_F, g.rho, g.t);
  const double alpha = (n - 1) * tau_F;  // (3.11)
  const double rThD = link_radius(theta_D, g.rho, g.t);
  const double xA = -rThD + (1.0 + s - z), yA = 0.0;
  const double xB = xA + (rThD - rF) * std::cos(theta_D), yB = yA + (rThD - rF) * std::sin(theta_D);
  struct End {
    double x, y;
  };
  auto end_point = [&](double thC) {  // (3.10)
    const double rThC = link_radius(thC, g.rho, g.t);
    const double xC = xB - (rThC - rF) * std::cos(theta_D + alpha);
    const double yC = yB - (rThC - rF) * std::sin(theta_D + alpha);
    return End{xC - (1.0 - rThC) * std::cos(theta_D + alpha + thC), yC - (1.0 - rThC) * std::sin(theta_D + alpha + thC)};
  };
  auto f = [&](double thC) {  // (3.13)
    const End d = end_point(thC);
    return std::hypot(d.x, d.y) - s;
  };
  // Scan for the first sign change in a generous range of θ_C, then bisect.
  const double step = 0.01 * pi / 180.0;
  double a = step, fa = f(a);
  double b = a;
  bool found = false;
  for (int k = 0; k < 6000; ++k) {
    b = a + step;
    const double fb = f(b);
    if (std::isfinite(fa) && std::isfinite(fb) && fa * fb <= 0.0) {
      found = true;
      break;
    }
    a = b;
    fa = fb;
  }
  if (!found) throw std::invalid_argument("transition kinematics: no closing angle theta_C found");
  for (int k = 0; k < 100; ++k) {
    const double m = 0.5 * (a + b), fm = f(m);
    if (fa * fm <= 0.0) {
      b = m;
    } else {
      a = m;
      fa = fm;
    }
  }
  TransitionKinematics r;
  r.theta_C = 0.5 * (a + b);
  const End d = end_point(r.theta_C);
  r.phi_D = std::asin(std::abs(d.y) / s);                       // (3.12)
  r.phi_C = pi - (r.phi_D + theta_D + alpha + r.theta_C);
  return r;
}

ContinuousBelt continuous_belt(double s, double z, double mu_D, double mu_C, double beta, int lambda) {
  ContinuousBelt c;
  c.gamma = contact_angles(s, z, 0.0);  // corrected (2.9)–(2.11)
  const double gD = c.gamma.D, gC = c.gamma.C;
  const double m_D = std::exp(mu_D * gD / std::sin(beta));  // (2.42)
  const double m_C = std::exp(mu_C * gC);                   // (2.43)
  c.disc_limits = m_D <= m_C;
  if (c.disc_limits) {
    c.alpha_D = 0.0;
    c.alpha_C = (gC * mu_C - gD * mu_D / std::sin(beta)) / mu_C;  // (2.45) with corrected sign
  } else {
    c.alpha_C = 0.0;
    c.alpha_D = (gD * mu_D / std::sin(beta) - gC * mu_C) * std::sin(beta) / mu_D;  // (2.46)
  }
  const double x = mu_D / std::sin(beta) * (gD - c.alpha_D);
  const double ex = std::exp(x);
  c.F_P0 = 1.0 / (ex - 1.0);  // (2.47)
  c.F_P1 = ex * c.F_P0;       // (2.49)
  c.F_A = c.F_P0 / std::tan(beta) * ((ex - 1.0) * std::sin(beta) + mu_D * c.alpha_D) / (lambda * mu_D);  // (2.50)
  c.F_N = c.F_P0 * (ex - 1.0 + mu_D * c.alpha_D / std::sin(beta)) / (lambda * mu_D);                     // (2.51)
  const double kC = gC - c.alpha_C;
  c.F_R = c.F_P0 * (-1.0 + std::exp(mu_C * kC) * (1.0 - mu_C * kC + mu_C * gC)) / mu_C;  // (2.52)
  return c;
}

double min_self_releasing_cone_angle(double mu, double mu_SU) {
  return std::acos(std::abs(-1.0 + mu * mu_SU) / std::sqrt((1.0 + mu * mu) * (1.0 + mu_SU * mu_SU)));  // (4.5)
}

}  // namespace mechsim::models::cvt
