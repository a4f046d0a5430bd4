// The HCVT push-belt CVT model, spec cvt.md §3–§5 and §8 (equation numbers are the thesis's,
// code names those of its appendix-B3 MATLAB program, whose order this follows).
#include "mechsim/models/cvt/cvt_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mechsim/models/constants.h"

namespace mechsim::models::cvt {

namespace {

constexpr int kMaxPushSteps = 20000;  // F_P0 steps of duwproc·T/r before "no solution"

// One contact arc as FF_tabel sees it.
struct ArcSpec {
  bool disc = true;      // disc contact (else the intermediate body C)
  bool driving = false;  // this body drives: its rest links are on the F_P0 side
  int n = 0;
  double tau = 0.0, theta = 0.0, q = 0.0, mu = 0.0, beta = 0.0, F_C = 0.0;
  const std::vector<double>* T = nullptr;  // μ^D_SU,tan(j) ≥ 0 (disc contact of the split belt)
  const std::vector<double>* R = nullptr;  // μ^D_SU,rad(j) ≥ 0
};

// FF_forces: march over the links j = 1..n from F_P0 with n_alpha rest links, (4.54)–(4.57).
ArcForces march(const ArcSpec& a, double FP0, int n_alpha, const CvtParams& p) {
  const double lam = p.lambda, cb = std::cos(a.beta), sb = std::sin(a.beta);
  ArcForces f;
  f.F_P.assign(a.n + 1, 0.0);
  f.F_N.assign(a.n, 0.0);
  f.F_A.assign(a.n, 0.0);
  f.F_W.assign(a.n, 0.0);
  f.F_WST.assign(a.n, 0.0);
  f.F_WSR.assign(a.n, 0.0);
  f.F_P[0] = FP0;
  for (int j = 1; j <= a.n; ++j) {
    const bool rest = a.driving ? j <= n_alpha : j > a.n - n_alpha;
    double xi1 = a.tau, xi2 = a.tau, mu1 = 0.0, mu2 = 0.0;
    if (j == 1) {
      mu1 = a.q;
      xi1 = a.theta;
    } else if (j == a.n) {
      mu2 = a.q;
      xi2 = a.theta;
    }
    if (!p.full_angle) {  // the text's Table 4-2 (half angles); does not reproduce the thesis
      xi1 /= 2.0;
      xi2 /= 2.0;
    }
    double muST = 0.0, muSR = 0.0;
    if (a.disc) {
      const double Tj = a.T ? (*a.T)[j - 1] : 0.0, Rj = a.R ? (*a.R)[j - 1] : 0.0;
      const bool first_half = j <= a.n / 2.0;
      if (a.driving) {  // geval 1
        muST = -Tj;
        muSR = first_half ? Rj : -Rj;
      } else {  // geval 2 (test rig)
        muST = Tj;
        muSR = first_half ? -Rj : Rj;
      }
    } else {  // geval 3/4
      muST = rest ? 0.0 : p.mu_SUC;
    }
    const double c1 = std::cos(xi1), s1 = std::sin(xi1), c2 = std::cos(xi2), s2 = std::sin(xi2);
    const double A = lam * sb - muSR * cb;
    const double P = f.F_P[j - 1];
    double mu = a.mu;
    if (rest) {  // (4.57): the friction that keeps F_P constant
      const double FN_hat = (a.F_C + P * (s1 + s2 + mu1 * c1 + mu2 * c2)) / A;
      mu = (P * ((c2 - mu2 * s2) - (c1 - mu1 * s1)) / FN_hat - muST * cb) / lam;
    }
    const double B = lam * mu + muST * cb;
    const double Pn = (B * a.F_C + P * (B * (s1 + mu1 * c1) + A * (c1 - mu1 * s1))) /
                      (A * (c2 - mu2 * s2) - B * (s2 + mu2 * c2));  // (4.54)
    const double FN = (a.F_C + Pn * (s2 + mu2 * c2) + P * (s1 + mu1 * c1)) / A;  // (4.55)
    f.F_P[j] = Pn;
    f.F_N[j - 1] = FN;
    f.F_A[j - 1] = cb * FN;  // (4.56)
    f.F_W[j - 1] = mu * FN;
    f.F_WST[j - 1] = muST * cb * FN;
    f.F_WSR[j - 1] = muSR * cb * FN;
  }
  return f;
}

ArcForces blend(const ArcForces& a, const ArcForces& b, double w) {
  auto mix = [w](const std::vector<double>& x, const std::vector<double>& y) {
    std::vector<double> r(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) r[i] = x[i] + w * (y[i] - x[i]);
    return r;
  };
  return {mix(a.F_P, b.F_P), mix(a.F_N, b.F_N), mix(a.F_A, b.F_A),
          mix(a.F_W, b.F_W), mix(a.F_WST, b.F_WST), mix(a.F_WSR, b.F_WSR)};
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}
double max_of(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

// Transmitted friction of one run: λ ΣF_W (+ the C-side terms of (4.65)).
struct Sweep {
  std::vector<double> koppel;  // F_W,KOPPEL(n_α), n_α = 0..n
  ArcForces last;              // the run with n_α = n (the code's loop variable after the loop)
};

template <class Koppel>
Sweep sweep(const ArcSpec& a, double FP0, const CvtParams& p, Koppel koppel) {
  Sweep s;
  for (int i = 0; i <= a.n; ++i) {
    ArcForces f = march(a, FP0, i, p);
    s.koppel.push_back(koppel(f));
    if (i == a.n) s.last = std::move(f);
  }
  return s;
}

// n_α at which the arc carries T/r (linear inverse interpolation) and the forces there
// (FF_forcesinterp). False unless F_W(0) > T/r >= F_W(n).
bool carry(const ArcSpec& a, const Sweep& s, double Tr, double FP0, const CvtParams& p, double& n_alpha,
           ArcForces& forces) {
  const auto& k = s.koppel;
  if (!(k.front() > Tr && Tr >= k.back())) return false;
  n_alpha = static_cast<double>(a.n);
  for (int i = 0; i < a.n; ++i) {
    if (k[i] >= Tr && Tr >= k[i + 1]) {
      n_alpha = k[i] == k[i + 1] ? i : i + (k[i] - Tr) / (k[i] - k[i + 1]);
      break;
    }
  }
  int f0 = static_cast<int>(std::floor(n_alpha));
  if (f0 >= a.n) f0 = a.n - 1;
  forces = blend(march(a, FP0, f0, p), march(a, FP0, f0 + 1, p), n_alpha - f0);
  return true;
}

// FF_krovgeb: friction q_D, q_C needed at the transition-packet ends and the push-force
// ratio VP on the 5×5 grid of θ_D, θ_C; c = C/P_D.
struct Packet {
  double qD_mean = 0.0, qC_mean = 0.0, max_dev_VP = 0.0;
};
Packet packet(double c, const BeltShape& b, const LinkGeometry& g) {
  Packet r;
  const double rf = b.rf, t = g.t, rho = g.rho, psi = b.psi;
  for (int i = 0; i < 5; ++i) {
    const double thD = b.tau_D + (b.tau_F - b.tau_D) * i / 4.0;
    for (int k = 0; k < 5; ++k) {
      const double thC = b.tau_C + (b.tau_F - b.tau_C) * k / 4.0;
      const double xi1 = (psi + thD) / 2.0, xi2 = (psi + thC) / 2.0;
      const double lPD = rf * std::cos(thD / 2.0) + 0.5 * (1.0 - 2.0 * rho) * t * std::sin(thD / 2.0);
      const double lPC = rf * std::cos(thC / 2.0) + 0.5 * (1.0 - 2.0 * rho) * t * std::sin(thC / 2.0);
      const double lWD = (link_radius(thD, rho, t) - rf) * std::sin(thD / 2.0);
      const double lWC = (link_radius(thC, rho, t) - rf) * std::sin(thC / 2.0);
      const double cs = std::cos(xi1 + xi2), sn = std::sin(xi1 + xi2);
      const double den = lWD + lWC * cs + lPC * sn;
      // The printed VP has sin ξ1 in both arms of the c-term (spec §3.5): kept as coded.
      const double VP = c * (lWC * std::sin(xi1) - lWD * std::sin(xi1)) / den + (lWC + lWD * cs + lPD * sn) / den;
      const double qD = c * (lWC * std::cos(xi2) + lPC * std::sin(xi2)) / den + (lPD - lPC * cs + lWC * sn) / den;
      const double qC = (lPC + c * lWD * std::cos(xi2) - lPD * cs + c * lPC * std::sin(xi1) + lWD * sn) /
                        (lWC + lWD * cs + c * lWC * std::sin(xi1) - c * lWD * std::sin(xi2) + lPD * sn);
      r.qD_mean += qD / 25.0;
      r.qC_mean += qC / 25.0;
      r.max_dev_VP = std::max(r.max_dev_VP, std::abs(1.0 - VP));
    }
  }
  return r;
}

bool finite_all(std::initializer_list<double> v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

std::string flag_names(unsigned flags) {
  static const std::pair<unsigned, const char*> names[] = {
      {kOutsideValidatedRange, "outside_validated_range"}, {kGrossSlip, "gross_slip"},
      {kStressExceeded, "stress_exceeded"}, {kLinkShift, "link_shift"}, {kZeroTorque, "zero_torque"},
      {kTorqueReversal, "torque_reversal"}, {kZeroSpeed, "zero_speed"}, {kNoSolution, "no_solution"},
      {kBadInput, "bad_input"}};
  std::string out;
  for (const auto& [bit, name] : names) {
    if (flags & bit) {
      if (!out.empty()) out += ",";
      out += name;
    }
  }
  return out;
}

CvtModel::CvtModel(CvtParams params)
    : p_(params), curv_(design_link_curvatures(params)), shapes_(LinkGeometry::from(params), params.acc) {
  const CvtParams& p = p_;
  auto bad = [](const std::string& what) { throw CvtInputError("CVT parameters: " + what); };
  if (p.lambda != 1 && p.lambda != 2) bad("lambda must be 1 (split belt) or 2 (Lambda belt)");
  if (!finite_all({p.r_C, p.link_thickness, p.rocking_radius, p.closing_angle, p.filling_degree, p.link_mass,
                   p.beta_D, p.beta_C, p.mu_D, p.mu_C, p.mu_E, p.mu_SUC, p.mu_SU, p.sigma_admissible, p.E_R,
                   p.t_D, p.l_D, p.t_C, p.l_C, p.l_E, p.A_SU, p.grease_viscosity, p.duwproc}))
    bad("every parameter must be a finite number");
  if (!(p.r_C > 0 && p.link_thickness > 0 && p.rocking_radius > 0 && p.link_mass >= 0 && p.t_D > 0 && p.l_D > 0 &&
        p.t_C > 0 && p.l_C > 0 && p.l_E > 0 && p.A_SU > 0 && p.E_R > 0 && p.sigma_admissible > 0))
    bad("lengths, areas, moduli and the admissible stress must be > 0 (link mass >= 0)");
  if (!(p.filling_degree > 0.9 && p.filling_degree < 1.0)) bad("filling degree bv must lie in (0.9, 1)");
  if (!(p.closing_angle > 0 && p.closing_angle < pi / 4)) bad("closing angle tau_S must lie in (0, 45 deg)");
  if (!(p.beta_D > 0 && p.beta_D < pi / 2 && p.beta_C > 0 && p.beta_C < pi / 2))
    bad("cone angles must lie in (0, 90 deg)");
  if (!(p.mu_D > 0 && p.mu_C > 0 && p.mu_E >= 0 && p.mu_SU >= 0 && p.mu_SUC >= 0))
    bad("friction coefficients mu_D, mu_C must be > 0, the others >= 0");
  if (!(p.duwproc > 0 && p.duwproc <= 1)) bad("duwproc (push-force step / (T/r)) must lie in (0, 1]");
  if (p.acc < 1 || p.acc > 3) bad("acc (belt-shape resolution) must be 1, 2 or 3");
}

void CvtModel::tabulate_shapes(double s_lo, double s_hi, int points) {
  if (!finite_all({s_lo, s_hi}) || !(s_lo > 0) || !(s_hi > s_lo) || points < 2)
    throw CvtInputError("belt-shape table: need 0 < s_lo < s_hi and at least 2 points");
  try {
    shapes_.tabulate(s_lo / p_.r_C, s_hi / p_.r_C, points);
  } catch (const std::invalid_argument& e) {
    throw CvtInputError(std::string("belt-shape table: ") + e.what());
  }
}

BeltShape CvtModel::shape(double s) { return checked_shape(s, false); }

BeltShape CvtModel::shape_scalars(double s) { return checked_shape(s, true); }

BeltShape CvtModel::checked_shape(double s, bool scalars_only) {
  if (!std::isfinite(s)) throw CvtInputError("ratio setting s is not a finite number");
  if (!(s > 0.0)) throw CvtInputError("ratio setting s must be > 0 (disc axis offset), got " + std::to_string(s) + " m");
  BeltShape b;
  try {
    b = scalars_only ? shapes_.scalars_at(s / p_.r_C) : shapes_.at(s / p_.r_C);
  } catch (const std::invalid_argument& e) {
    throw CvtInputError("ratio setting s = " + std::to_string(s * 1e3) + " mm is outside the geometric range: " + e.what());
  }
  if (b.n_D < 2 || b.n_C < 2 || !(b.psi > 0.0))
    throw CvtInputError("ratio setting s = " + std::to_string(s * 1e3) +
                        " mm is outside the geometric range: fewer than 2 links in a contact or no transition packet");
  return b;
}

BearingLoads CvtModel::bearing_losses(bool primary, double r, double omega, double F_K, double Tr) const {
  // Appendix B2 (code FC_TLprim / FC_TLsec): SKF formulas in mm, N, rpm, mm²/s.
  const ShaftBearings& sb = primary ? p_.primary : p_.secondary;
  const double mm = 1e3;
  const double rr = r * mm, tb = std::tan(p_.beta_D);
  const double m1 = (sb.l1 + sb.A.pressure_centre + sb.B.pressure_centre) * mm;
  BearingLoads L;
  double FrA1, FrB1, m2;
  if (primary) {
    m2 = (sb.l2 - sb.B.pressure_centre) * mm;
    FrA1 = F_K * (rr - m2 * tb) / m1;
    FrB1 = F_K * (-rr + (m1 + m2) * tb) / m1;
  } else {  // code: + r_D tan β_D (text: sin), erratum 15
    m2 = (sb.l2 - sb.B.pressure_centre) * mm + rr * tb;
    FrA1 = F_K * (rr + m2 * tb) / m1;
    FrB1 = -F_K * (rr + (m1 + m2) * tb) / m1;
  }
  const double FrA2 = m2 * Tr / m1, FrB2 = -(m1 + m2) * Tr / m1;
  L.F_rA = std::hypot(FrA1, FrA2);
  L.F_rB = std::hypot(FrB1, FrB2);
  L.F_aA = 0.5 * L.F_rA / sb.A.axial_factor;  // SKF table B2-2 case 1, K_a = F_K
  L.F_aB = L.F_aA + F_K;
  const double n = std::abs(omega) * 60.0 / (2.0 * pi);
  const double nu = p_.grease_viscosity * 1e6;
  auto T_L0 = [&](double dm) {
    const double d3 = std::pow(dm * mm, 3.0);
    return nu * n >= 2000.0 ? 1e-10 * 6.0 * std::pow(nu * n, 2.0 / 3.0) * d3 : 1e-10 * 160.0 * 6.0 * d3;
  };
  auto T_L1 = [&](double Fr, double Fa, const TaperedBearing& b) {
    return 1e-3 * 0.0004 * std::max(Fr, 2.0 * b.axial_factor * Fa) * b.mean_diameter * mm;
  };
  L.T_L0A = T_L0(sb.A.mean_diameter);
  L.T_L0B = T_L0(sb.B.mean_diameter);
  L.T_L1A = T_L1(L.F_rA, L.F_aA, sb.A);
  L.T_L1B = T_L1(L.F_rB, L.F_aB, sb.B);
  return L;
}

CvtResult CvtModel::evaluate(const CvtOperatingPoint& op) {
  if (!finite_all({op.s, op.omega_C, op.torque, op.v_K, op.F_K_applied}))
    throw CvtInputError("CVT operating point: s, speed, torque, v_K and F_K must be finite numbers");
  if (op.omega_C < 0.0)
    throw CvtInputError("CVT operating point: input speed must be >= 0 (reverse rotation is outside the model)");
  if (op.clamp == ClampMode::safety_factor && !(op.v_K > 0.0))
    throw CvtInputError("CVT operating point: clamping reserve factor v_K must be > 0");
  if (op.clamp == ClampMode::clamping_force && op.F_K_applied < 0.0)
    throw CvtInputError("CVT operating point: clamping force must be >= 0, got " + std::to_string(op.F_K_applied) + " N");

  switch (op.torque_input) {
    case TorqueInput::intermediate_body:
      return evaluate_tc(op, op.torque, op.v_K);
    case TorqueInput::input_shaft: {
      // T_C = T_1 − T_Lprim(T_C): fixed point from T_C = T_1 (T_L ≪ T, 2–3 iterations; the
      // piecewise F_K may leave a last alternation, hence the iteration cap).
      double T_C = op.torque;
      CvtResult r = evaluate_tc(op, T_C, op.v_K);
      for (int k = 0; k < 30; ++k) {
        const double next = op.torque - r.T_L_prim;
        if (!std::isfinite(next)) break;
        const bool done = std::abs(next - T_C) < 1e-9 * std::max(1.0, std::abs(op.torque));
        T_C = next;
        r = evaluate_tc(op, T_C, op.v_K);
        if (done) break;
      }
      return r;
    }
    case TorqueInput::output_load: {
      // T_C = i_TH (T_2 + T_Lsec)/η_PB, from T_C = i_TH T_2.
      const double i = shape(op.s).ratio();
      double T_C = i * op.torque;
      CvtResult r = evaluate_tc(op, T_C, op.v_K);
      for (int k = 0; k < 30; ++k) {
        if (!belt_state_modelled(r.flags) || !(r.eta_PB > 0.0)) break;
        const double next = i * (op.torque + r.T_L_sec) / r.eta_PB;
        if (!std::isfinite(next)) break;
        const bool done = std::abs(next - T_C) < 1e-9 * std::max(1.0, std::abs(op.torque));
        T_C = next;
        r = evaluate_tc(op, T_C, op.v_K);
        if (done) break;
      }
      return r;
    }
  }
  return {};
}

namespace {

// The result's account of the operating point and the belt shape, before any force; flags a
// point outside the validated range or at rest.
CvtResult operating_point(const CvtParams& p, const BeltShape& b, const CvtOperatingPoint& op, double T_C) {
  CvtResult r;
  r.level = op.level;
  r.s = op.s;
  r.z_max = b.z * p.r_C;
  r.r_D = b.r_D() * p.r_C;
  r.r_F = b.rf * p.r_C;
  r.ratio = b.ratio();
  r.gamma_D = b.gamma_D;
  r.gamma_C = b.gamma_C;
  r.gamma_F = b.gamma_F;
  r.n_D = b.n_D;
  r.n_C = b.n_C;
  r.omega_C = op.omega_C;
  r.omega_D = r.ratio * op.omega_C;  // (4.60)
  r.T_C = T_C;
  r.T_over_r = T_C / p.r_C;      // (4.61)
  r.v_PB = op.omega_C * p.r_C;   // (4.62)
  r.slip = b.slip;
  r.F_K_applied = op.clamp == ClampMode::clamping_force ? op.F_K_applied : nan;

  const double tol = 1e-9;
  if (op.s < p.s_min - tol || op.s > p.s_max + tol || T_C < p.torque_min - tol || T_C > p.torque_max + tol ||
      op.omega_C < p.speed_min * (1 - tol) || op.omega_C > p.speed_max * (1 + tol))
    r.flags |= kOutsideValidatedRange;
  if (op.omega_C == 0.0) r.flags |= kZeroSpeed;
  return r;
}

}  // namespace

void CvtModel::unloaded(CvtResult& r, const CvtOperatingPoint& op, double T_C) const {
  // Unloaded (or reversed) belt: the thesis's algorithm is undefined (F_P0 step = 0).
  const double cbD = std::cos(p_.beta_D);
  r.flags |= T_C == 0.0 ? kZeroTorque : kTorqueReversal;
  r.F_K = op.clamp == ClampMode::clamping_force ? op.F_K_applied : 0.0;
  r.v_K = nan;
  r.bearings_prim = bearing_losses(true, p_.r_C, op.omega_C, r.F_K, r.T_over_r);
  r.bearings_sec = bearing_losses(false, r.r_D, r.omega_D, r.F_K, r.T_over_r);
  r.T_L_prim = r.bearings_prim.loss_torque();
  r.T_L_sec = r.bearings_sec.loss_torque();
  r.T_1 = T_C + r.T_L_prim;
  r.T_C_capacity = p_.r_C * p_.lambda * p_.mu_D * r.F_K / cbD;
  if (T_C == 0.0) {
    r.eta_PB = 1.0;
    r.P_loss_belt = 0.0;
    r.T_D = 0.0;
    r.T_2 = -r.T_L_sec;
    r.eta_L_prim = r.eta_L_sec = r.eta_SYS = 0.0;  // no power transmitted
  } else {
    r.eta_PB = r.eta_L_prim = r.eta_L_sec = r.eta_SYS = r.P_loss_belt = r.T_D = r.T_2 = nan;
  }
}

void CvtModel::gross_slip(CvtResult& r, const CvtOperatingPoint& op, double T_C, double v_K) const {
  const double cbD = std::cos(p_.beta_D);
  r.flags |= kGrossSlip;
  r.v_K = v_K;
  r.v_KD = v_K;
  r.F_K = op.F_K_applied;
  r.bearings_prim = bearing_losses(true, p_.r_C, op.omega_C, r.F_K, r.T_over_r);
  r.bearings_sec = bearing_losses(false, r.r_D, r.omega_D, r.F_K, r.T_over_r);
  r.T_L_prim = r.bearings_prim.loss_torque();
  r.T_L_sec = r.bearings_sec.loss_torque();
  r.T_1 = T_C + r.T_L_prim;
  r.eta_PB = r.eta_L_sec = r.eta_SYS = r.P_loss_belt = r.T_D = r.T_2 = r.v_KC = nan;
  r.eta_L_prim = T_C / r.T_1;
  r.mu_D_required = cbD * r.T_over_r / (p_.lambda * op.F_K_applied);
  r.sigma.fill(nan);
}

CvtResult CvtModel::evaluate_tc(const CvtOperatingPoint& op, double T_C, double v_K) {
  const BeltShape b = shape(op.s);
  CvtResult r = operating_point(p_, b, op, T_C);
  if (T_C <= 0.0) {
    unloaded(r, op, T_C);
    return r;
  }
  if (op.clamp == ClampMode::clamping_force) {
    const double cbD = std::cos(p_.beta_D);
    // v_KD = λ μ_D F_K/(cos β_D T/r) (4.64) with (4.56), (4.67).
    v_K = p_.lambda * p_.mu_D * op.F_K_applied / (cbD * r.T_over_r);
    r.T_C_capacity = p_.r_C * p_.lambda * p_.mu_D * op.F_K_applied / cbD;
    if (v_K < 1.0) {
      gross_slip(r, op, T_C, v_K);
      return r;
    }
  }
  r.v_K = v_K;
  if (op.level == Level::L1) {
    solve_l1(r, b, v_K);
  } else {
    solve_l0(r, b, v_K);
  }
  if (r.flags & kNoSolution) {
    r.eta_PB = r.eta_L_prim = r.eta_L_sec = r.eta_SYS = r.P_loss_belt = r.T_D = r.T_2 = r.T_1 = r.F_K = nan;
    return r;
  }
  finish(r, b);
  return r;
}

double CvtModel::min_push_force(CvtResult& r, const BeltShape& b, const LinkGeometry& g) const {
  const CvtParams& p = p_;
  const double v = r.v_PB;
  // e. centrifugal forces (4.13); f. transition packet (4.29)–(4.31), F_Pmin (4.35).
  r.F_C_D = p.link_mass * v * v / r.r_D;
  r.F_C_C = p.link_mass * v * v / p.r_C;
  const double nFd = 1.0 + b.psi / b.tau_F;
  r.F_C_packet = nFd * p.link_mass * v * v / (b.rf * p.r_C);
  const double step = p.duwproc * r.T_over_r;
  for (int k = 1; k <= kMaxPushSteps; ++k) {
    const double cand = k * step;
    if (packet(r.F_C_packet / cand, b, g).max_dev_VP <= 0.025) return cand;
    if (r.F_C_packet == 0.0) break;  // VP does not depend on k: no push force will do
  }
  return 0.0;
}

void CvtModel::solve_l1(CvtResult& r, const BeltShape& b, double v_K) {
  const CvtParams& p = p_;
  const LinkGeometry g = shapes_.geometry();
  const double Tr = r.T_over_r, v = r.v_PB, lam = p.lambda;
  const bool split = p.lambda == 1 && p.mu_SU > 0.0;
  const double step = p.duwproc * Tr;
  const double FPmin = min_push_force(r, b, g);
  if (FPmin == 0.0) {
    r.flags |= kNoSolution;
    return;
  }
  r.F_P_min = FPmin;

  // Support-surface friction components of the split belt per disc link (§3.3).
  std::vector<double> T(b.n_D, 0.0), R(b.n_D, 0.0), muC(b.n_D, 0.0);
  if (split) {
    for (int j = 0; j < b.n_D; ++j) {
      T[j] = p.mu_SU * b.cos_eps_D[j];
      R[j] = p.mu_SU * b.sin_eps_D[j];
      muC[j] = p.mu_SU * (p.quirk_muSUC_radial ? b.sin_eps_C[j] : b.cos_eps_C[j]);
    }
  }
  ArcSpec D{true, p.disc_driving, b.n_D, b.tau_D, b.theta_D, 0.0, p.mu_D, p.beta_D, r.F_C_D, &T, &R};
  ArcSpec C{false, !p.disc_driving, b.n_C, b.tau_C, b.theta_C, 0.0, p.mu_C, p.beta_C, r.F_C_C, nullptr, nullptr};
  const double sign3 = p.disc_driving ? 1.0 : -1.0;  // (4.65) 3rd term: − when C drives

  // g. FF_kps: raise F_P0 in steps of duwproc·T/r until both contacts carry T/r with v_K.
  double FP0 = FPmin;
  for (int it = 0; it < kMaxPushSteps; ++it, FP0 += step) {
    const Packet pk = packet(r.F_C_packet / FP0, b, g);
    D.q = std::clamp(pk.qD_mean, -p.mu_E, p.mu_E);
    C.q = std::clamp(pk.qC_mean, -p.mu_E, p.mu_E);
    const Sweep sd = sweep(D, FP0, p, [&](const ArcForces& f) { return lam * sum(f.F_W); });
    double naD = 0.0, naC = 0.0;
    ArcForces fD, fC;
    if (!carry(D, sd, Tr, FP0, p, naD, fD)) continue;
    const double vKD = lam * p.mu_D * sum(fD.F_N) / Tr;  // (4.64)
    if (vKD < v_K) continue;
    // Torque the support surface delivers straight to C while the belt is in the disc contact.
    const std::vector<double>& FA3 = p.quirk_last_sweep_FA ? sd.last.F_A : fD.F_A;
    double third = 0.0;
    for (int j = 0; j < b.n_D; ++j) third += muC[j] * FA3[j] * b.r_su[j];
    const Sweep sc = sweep(C, FP0, p, [&](const ArcForces& f) {
      return lam * sum(f.F_W) + sum(f.F_WST) + sign3 * third;  // (4.65)
    });
    if (!carry(C, sc, Tr, FP0, p, naC, fC)) continue;
    const double vKC = (lam * p.mu_C * sum(fC.F_N) + p.mu_SUC * sum(fC.F_A)) / Tr;  // (4.66)
    if (vKC < v_K) continue;
    if (std::abs(pk.qD_mean) > p.mu_E || std::abs(pk.qC_mean) > p.mu_E) r.flags |= kLinkShift;
    r.F_P0 = FP0;
    r.q_D = D.q;
    r.q_C = C.q;
    r.n_alpha_D = naD;
    r.n_alpha_C = naC;
    r.v_KD = vKD;
    r.v_KC = vKC;
    r.disc = std::move(fD);
    r.ring = std::move(fC);
    // h. clamping force (4.67) and the peak forces; i. stresses.
    const double FK = sum(r.disc.F_A);
    r.F_K = p.round_clamping_force ? std::round(FK) : FK;
    r.F_N_peak = {max_of(r.disc.F_N), max_of(r.ring.F_N), std::max(max_of(r.disc.F_P), max_of(r.ring.F_P)),
                  std::max(max_of(r.disc.F_A), max_of(r.ring.F_A))};
    r.F_P_max = r.F_N_peak[2];
    r.sigma = {sigma_link_disc(r.F_N_peak[0], r.r_D, p, curv_), sigma_link_ring(r.F_N_peak[1], p, curv_),
               sigma_link_link(r.F_N_peak[2], p).sigma_eq, sigma_support(r.F_N_peak[3], p)};
    // j. belt loss (6.1): macroslip of the split belt on the support surface.
    r.P_loss_belt = 0.0;
    if (split)
      for (int j = 0; j < b.n_D; ++j) r.P_loss_belt += p.mu_SU * r.disc.F_A[j] * b.slip[j] * v;
    return;
  }
  r.flags |= kNoSolution;
}

void CvtModel::solve_l0(CvtResult& r, const BeltShape& b, double v_K) {
  // Closed form (spec §8.3): F_K = v_K cos β_D (T/r)/(λ μ_D) (2.50)/(2.54) with α_D = 0;
  // η_PB from the mean slip; no link forces, hence no stresses.
  const CvtParams& p = p_;
  const double cb = std::cos(p.beta_D);
  r.F_K = v_K * cb * r.T_over_r / (p.lambda * p.mu_D);
  r.v_KD = v_K;
  r.v_KC = nan;
  r.sigma.fill(nan);
  r.F_N_peak.fill(nan);
  const bool split = p.lambda == 1 && p.mu_SU > 0.0;
  const double loss_fraction = split ? (p.mu_SU / p.mu_D) * (cb / p.lambda) * b.mean_slip() : 0.0;
  r.P_loss_belt = loss_fraction * r.T_over_r * r.v_PB;
}

void CvtModel::finish(CvtResult& r, const BeltShape& b) {
  const CvtParams& p = p_;
  const double Tr = r.T_over_r;
  r.v_slip_max = max_of(b.slip) * r.v_PB;
  if (r.v_PB > 0.0) {
    r.eta_PB = 1.0 - r.P_loss_belt / (Tr * r.v_PB);  // (6.2)
  } else {
    r.P_loss_belt = 0.0;
    r.eta_PB = 1.0;  // no slip power at standstill
  }
  if (!(r.eta_PB > 0.0)) {
    // A tiny T_C at speed: the centrifugally clamped belt's slip loss exceeds T_C ω_C, so the
    // output torque would reverse. Outside the model: flagged, no efficiency.
    r.flags |= kTorqueReversal;
    r.eta_PB = nan;
  }
  r.mu_D_required = std::cos(p.beta_D) * Tr / (p.lambda * r.F_K);
  r.T_C_capacity = p.r_C * p.lambda * p.mu_D * r.F_K / std::cos(p.beta_D);
  for (int i = 0; i < 4; ++i)
    if (std::isfinite(r.sigma[i]) && r.sigma[i] > p.sigma_admissible) r.flags |= kStressExceeded;
  // Bearings with the (rounded) F_K, as coded; then (6.3)–(6.10).
  r.bearings_prim = bearing_losses(true, p.r_C, r.omega_C, r.F_K, Tr);
  r.bearings_sec = bearing_losses(false, r.r_D, r.omega_D, r.F_K, Tr);
  r.T_L_prim = r.bearings_prim.loss_torque();
  r.T_L_sec = r.bearings_sec.loss_torque();
  r.T_1 = r.T_C + r.T_L_prim;
  r.T_D = r.eta_PB * r.T_C / r.ratio;
  r.T_2 = r.T_D - r.T_L_sec;
  r.eta_L_prim = r.T_C / r.T_1;
  r.eta_L_sec = r.T_2 / r.T_D;
  r.eta_SYS = r.eta_L_prim * r.eta_PB * r.eta_L_sec;
}

}  // namespace mechsim::models::cvt
