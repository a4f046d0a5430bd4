#include "mechsim/models/cvt/cvt_block.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <vector>

namespace mechsim::models::cvt {

namespace {

// Everything the belt-shape table depends on: the model's parameters (compared member by
// member: a field added to CvtParams is part of the key by itself) and the table's range.
struct ShapesKey {
  CvtParams cvt;
  double s_min, s_max;
  int points;
  auto operator<=>(const ShapesKey&) const = default;
};
ShapesKey shapes_key(const CvtBlockParams& p) { return {p.cvt, p.s_table_min, p.s_table_max, p.s_table_points}; }

// ... and the belt map: the shapes, the level, the safety factor and the grid.
struct BeltTableKey {
  ShapesKey shapes;
  double v_K;
  Level level;
  int s_points, torque_points, speed_points;
  auto operator<=>(const BeltTableKey&) const = default;
};
BeltTableKey belt_table_key(const CvtBlockParams& p) {
  return {shapes_key(p), p.v_K, p.level, p.table_s_points, p.table_torque_points, p.table_speed_points};
}

// Both tables are pure functions of their keys and cost ~0.1-0.3 s each (belt-shape searches,
// L1 evaluations): built once per parameter set and process, so that the bench's in-process
// runs and references (hundreds of blocks with the same parameters) share them. A failed build
// throws and caches nothing.
std::mutex cache_mutex;

// Sets `value` from the cache under `key`, or builds it with `build()` and caches it.
template <typename Key, typename Value, typename Build>
void from_cache(std::map<Key, Value>& cache, const Key& key, Value& value, Build build) {
  {
    std::lock_guard<std::mutex> lock(cache_mutex);
    if (auto it = cache.find(key); it != cache.end()) {
      value = it->second;
      return;
    }
  }
  build();
  std::lock_guard<std::mutex> lock(cache_mutex);
  cache.emplace(key, value);
}

}  // namespace

CvtBlock::CvtBlock(CvtBlockParams params) : Block("cvt"), p_(std::move(params)), model_(p_.cvt) {
  if (!(p_.J_C > 0 && p_.J_D >= 0 && p_.stall_torque > 0 && p_.no_load_speed > 0 && p_.ratio_time_constant > 0))
    throw CvtInputError("cvt block: J_C, stall torque, no-load speed and ratio time constant must be > 0, J_D >= 0");
  if (!(p_.s_table_min > 0 && p_.s_table_max > p_.s_table_min && p_.s_table_points >= 2))
    throw CvtInputError("cvt block: the shape table needs 0 < s_min < s_max and at least 2 points");
  if (!(p_.s0 >= p_.s_table_min && p_.s0 <= p_.s_table_max))
    throw CvtInputError("cvt block: the initial ratio setting must lie in the tabulated range");
  if (!(std::isfinite(p_.omega0) && p_.omega0 >= 0))
    throw CvtInputError("cvt block: the initial input speed must be finite and >= 0");
  for (std::size_t k = 0; k < p_.ratio_schedule.size(); ++k) {
    const auto& [t, s] = p_.ratio_schedule[k];
    if (!std::isfinite(t) || (k > 0 && t < p_.ratio_schedule[k - 1].first))
      throw CvtInputError("cvt block: the ratio schedule's times must be finite and non-decreasing");
    if (!(s >= p_.s_table_min && s <= p_.s_table_max))
      throw CvtInputError("cvt block: every ratio setting of the schedule must lie in the tabulated range");
  }
  tabulate_shapes();
  if (p_.belt_table) {
    if (p_.clamp != ClampMode::safety_factor)
      throw CvtInputError("cvt block: the tabulated belt map needs safety-factor clamping (use direct evaluation with a clamping force)");
    if (p_.table_s_points < 2 || p_.table_torque_points < 2 || p_.table_speed_points < 2)
      throw CvtInputError("cvt block: the belt map needs at least 2 points per axis");
    build_table();
  }

  if (p_.ratio_schedule.empty()) in_.ratio_command = declare_input("ratio_command", "m", p_.s0);
  in_.load_torque = declare_input("load_torque", "N m", 0.0);
  in_.load_inertia = declare_input("load_inertia", "kg m^2", 0.0);
  const std::vector<int> ft{in_.load_torque, in_.load_inertia};
  out_.input_speed = declare_output("input_speed", "rad/s");
  out_.output_speed = declare_output("output_speed", "rad/s");
  out_.ratio = declare_output("ratio", "1");
  out_.ratio_setting = declare_output("ratio_setting", "m");
  out_.motor_torque = declare_output("motor_torque", "N m");
  out_.belt_torque = declare_output("belt_torque", "N m", ft);
  out_.input_torque = declare_output("input_torque", "N m", ft);
  out_.output_torque = declare_output("output_torque", "N m", ft);
  out_.eta_PB = declare_output("eta_PB", "1", ft);
  out_.eta_SYS = declare_output("eta_SYS", "1", ft);
  out_.clamping_force = declare_output("clamping_force", "N", ft);
  out_.slip_margin = declare_output("slip_margin", "1", ft);
  out_.sigma1 = declare_output("sigma_1", "Pa", ft);
  out_.sigma2 = declare_output("sigma_2", "Pa", ft);
  out_.sigma3 = declare_output("sigma_3", "Pa", ft);
  out_.sigma4 = declare_output("sigma_4", "Pa", ft);
  out_.belt_loss = declare_output("belt_loss", "W", ft);
  out_.bearing_loss = declare_output("bearing_loss", "W", ft);
  out_.flags = declare_output("flags", "1", ft);
  out_.output_acceleration = declare_output("output_acceleration", "rad/s^2", ft);
  const std::vector<int> cmd_ft = in_.ratio_command >= 0 ? std::vector<int>{in_.ratio_command} : std::vector<int>{};
  out_.ratio_command = declare_output("ratio_command", "m", cmd_ft);
  out_.motor_power = declare_output("motor_power", "W");
  out_.kinetic_energy = declare_output("kinetic_energy", "J");
  out_.gross_slip = declare_output("gross_slip", "1", ft);
  out_.torque_reversal = declare_output("torque_reversal", "1", ft);
  out_.outside_model = declare_output("outside_model", "1", ft);
  st_.input_speed = declare_state("input_speed", "rad/s");
  st_.ratio_setting = declare_state("ratio_setting", "m");
  if (p_.clamp_time_constant > 0) {
    if (!p_.belt_table) throw CvtInputError("cvt block: the clamping actuator lag needs the tabulated belt map");
    st_.clamping_force = declare_state("clamping_force", "N");
    F_K0_ = p_.F_K0;
    if (F_K0_ < 0) {
      // The command at the initial state without load: the motor's torque on the belt.
      const double T = p_.stall_torque * (1.0 - p_.omega0 / p_.no_load_speed);
      F_K0_ = T > 0 ? table_belt(p_.s0, p_.omega0, T).F_K : 0.0;
    }
  } else if (p_.clamp_time_constant < 0 || !std::isfinite(p_.clamp_time_constant)) {
    throw CvtInputError("cvt block: the clamping time constant must be >= 0");
  }
}

void CvtBlock::initial_state(double, std::span<double> x) const {
  x[st_.input_speed] = p_.omega0;
  x[st_.ratio_setting] = p_.s0;
  if (st_.clamping_force >= 0) x[st_.clamping_force] = F_K0_;
}

void CvtBlock::apply_clamp_lag(CvtResult& r, double F_act, double F_cmd) const {
  if (!(F_cmd > 0 && r.T_over_r > 0)) return;  // unloaded or reversed: nothing to clamp against
  F_act = std::max(F_act, 0.0);
  r.F_K = F_act;
  r.v_KD *= F_act / F_cmd;
  if (F_act * p_.v_K < F_cmd) {  // below the need at v_K = 1: the belt slips
    r.flags |= kGrossSlip;
    r.T_C_capacity = r.T_C * F_act * p_.v_K / F_cmd;
  }
  r.bearings_prim = model_.bearing_losses(true, p_.cvt.r_C, r.omega_C, F_act, r.T_over_r);
  r.bearings_sec = model_.bearing_losses(false, r.r_D, r.omega_D, F_act, r.T_over_r);
  r.T_L_prim = r.bearings_prim.loss_torque();
  r.T_L_sec = r.bearings_sec.loss_torque();
}

double CvtBlock::ratio_command(double t, std::span<const double> u) const {
  if (in_.ratio_command >= 0) return u[in_.ratio_command];
  const auto& sch = p_.ratio_schedule;
  if (t <= sch.front().first) return sch.front().second;
  for (std::size_t k = 1; k < sch.size(); ++k) {
    if (t < sch[k].first) {
      const auto& [t0, s0] = sch[k - 1];
      const auto& [t1, s1] = sch[k];
      return s0 + (s1 - s0) * (t - t0) / (t1 - t0);  // t0 < t < t1 here: a step never divides by 0
    }
  }
  return sch.back().second;
}

void CvtBlock::tabulate_shapes() {
  // The model right after tabulating holds the shape table and no other searched shape: a
  // copy of it is the state this block would reach by searching itself.
  static std::map<ShapesKey, CvtModel> cache;
  from_cache(cache, shapes_key(p_), model_,
             [&] { model_.tabulate_shapes(p_.s_table_min, p_.s_table_max, p_.s_table_points); });
}

void CvtBlock::build_table() {
  static std::map<BeltTableKey, Table> cache;
  from_cache(cache, belt_table_key(p_), table_, [&] { compute_table(); });
}

void CvtBlock::compute_table() {
  Table& T = table_;
  const CvtParams& c = p_.cvt;
  T.ns = p_.table_s_points;
  T.nt = p_.table_torque_points;
  T.nw = p_.table_speed_points;
  T.s0 = p_.s_table_min;
  T.ds = (p_.s_table_max - p_.s_table_min) / (T.ns - 1);
  T.t0 = c.torque_min;
  T.dt = (c.torque_max - c.torque_min) / (T.nt - 1);
  T.w0 = c.speed_min;
  T.dw = (c.speed_max - c.speed_min) / (T.nw - 1);
  T.v.assign(static_cast<std::size_t>(T.ns * T.nt * T.nw * Table::kFields), 0.0);
  CvtOperatingPoint op;
  op.clamp = ClampMode::safety_factor;
  op.v_K = p_.v_K;
  op.level = p_.level;
  for (int is = 0; is < T.ns; ++is)
    for (int it = 0; it < T.nt; ++it)
      for (int iw = 0; iw < T.nw; ++iw) {
        op.s = std::min(T.s0 + is * T.ds, p_.s_table_max);
        op.torque = T.t0 + it * T.dt;
        op.omega_C = T.w0 + iw * T.dw;
        const CvtResult r = model_.evaluate(op);
        if (!belt_state_modelled(r.flags) || !std::isfinite(r.eta_PB))
          throw CvtInputError("cvt block: the belt map has no modelled state at s = " + std::to_string(op.s * 1e3) +
                              " mm, T_C = " + std::to_string(op.torque) + " N m (" + flag_names(r.flags) + ")");
        double* v = &T.v[static_cast<std::size_t>(((is * T.nt + it) * T.nw + iw) * Table::kFields)];
        v[0] = r.eta_PB;
        v[1] = r.F_K / r.T_over_r;
        v[2] = r.v_KD;
        for (int k = 0; k < 4; ++k) v[3 + k] = r.sigma[k];  // NaN at L0: interpolates to NaN
      }
}

CvtResult CvtBlock::table_belt(double s, double w, double T_C) const {
  const Table& T = table_;
  const CvtParams& c = p_.cvt;
  CvtResult r;
  r.level = p_.level;
  const BeltShape shape = model_.shape_scalars(s);
  r.s = s;
  r.ratio = shape.ratio();
  r.r_D = c.r_C * shape.r_D();
  r.omega_C = w;
  r.omega_D = r.ratio * w;
  r.T_C = T_C;
  r.T_over_r = T_C / c.r_C;
  r.v_PB = w * c.r_C;
  r.v_K = p_.v_K;
  if (s < c.s_min || s > c.s_max || T_C < c.torque_min || T_C > c.torque_max || w < c.speed_min || w > c.speed_max)
    r.flags |= kOutsideValidatedRange;
  if (w == 0.0) r.flags |= kZeroSpeed;
  if (T_C <= 0.0) {
    r.flags |= T_C == 0.0 ? kZeroTorque : kTorqueReversal;
    r.eta_PB = T_C == 0.0 ? 1.0 : NAN;
    r.F_K = 0.0;
  }
  // Trilinear interpolation, coordinates clamped to the table (outside: the edge's values, flagged above).
  auto cell = [](double x, double x0, double dx, int n, int& i, double& f) {
    double u = (x - x0) / dx;
    u = std::clamp(u, 0.0, static_cast<double>(n - 1));
    i = std::min(static_cast<int>(u), n - 2);
    f = u - i;
  };
  int is, it, iw;
  double fs, ft, fw;
  cell(s, T.s0, T.ds, T.ns, is, fs);
  cell(T_C, T.t0, T.dt, T.nt, it, ft);
  cell(w, T.w0, T.dw, T.nw, iw, fw);
  double v[Table::kFields] = {};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int d = 0; d < 2; ++d) {
        const double wgt = (a ? fs : 1 - fs) * (b ? ft : 1 - ft) * (d ? fw : 1 - fw);
        const double* src = &T.v[static_cast<std::size_t>((((is + a) * T.nt + it + b) * T.nw + iw + d) * Table::kFields)];
        for (int k = 0; k < Table::kFields; ++k) v[k] += wgt * src[k];
      }
  if (T_C > 0.0) {
    r.F_K = v[1] * r.T_over_r;
    r.v_KD = v[2];
    for (int k = 0; k < 4; ++k) r.sigma[k] = v[3 + k];
    // The slip loss (η_PB) is a fraction of T_C ω_C at the table's torques; a tiny torque
    // whose centrifugal slip loss would exceed it is not resolved by the table: flagged
    // through the range check (T_C < 20 N m) like every state below the map.
    r.eta_PB = v[0];
    r.P_loss_belt = (1.0 - r.eta_PB) * T_C * w;
  }
  for (double sig : r.sigma)
    if (sig > c.sigma_admissible) r.flags |= kStressExceeded;
  const double Tr = r.T_over_r > 0 ? r.T_over_r : 0.0;
  r.bearings_prim = model_.bearing_losses(true, c.r_C, w, r.F_K, Tr);
  r.bearings_sec = model_.bearing_losses(false, r.r_D, r.omega_D, r.F_K, Tr);
  r.T_L_prim = r.bearings_prim.loss_torque();
  r.T_L_sec = r.bearings_sec.loss_torque();
  r.T_1 = T_C + r.T_L_prim;
  if (std::isfinite(r.eta_PB)) {
    r.T_D = r.eta_PB * T_C / r.ratio;
    r.T_2 = r.T_D - r.T_L_sec;
    r.eta_SYS = r.T_1 != 0.0 ? (r.T_2 * r.omega_D) / (r.T_1 * w) : NAN;
  } else {
    r.T_2 = r.T_D = r.eta_SYS = NAN;
  }
  return r;
}

CvtResult CvtBlock::belt(double s, double omega_C, double T_C) const {
  if (p_.belt_table) return table_belt(s, omega_C, T_C);
  CvtOperatingPoint op;
  op.s = s;
  op.omega_C = omega_C;
  op.torque = T_C;
  op.clamp = p_.clamp;
  op.v_K = p_.v_K;
  op.F_K_applied = p_.F_K;
  op.level = p_.level;
  return model_.evaluate(op);
}

CvtBlock::Solution CvtBlock::solve(double t, std::span<const double> x, std::span<const double> u) const {
  Solution sol;
  unsigned bad = 0;
  double w = std::max(x[st_.input_speed], 0.0);  // the motor line does not reverse the shaft
  if (!std::isfinite(w)) {
    bad |= kBadInput;
    w = 0.0;
  }
  double s = x[st_.ratio_setting];
  if (!(s >= p_.s_table_min && s <= p_.s_table_max)) {
    bad |= kBadInput;
    s = std::isfinite(s) ? std::clamp(s, p_.s_table_min, p_.s_table_max) : p_.s0;
  }
  sol.s_cmd = ratio_command(t, u);
  if (!(sol.s_cmd >= p_.s_table_min && sol.s_cmd <= p_.s_table_max)) {
    // A command outside the geometric range: the actuator stops at its end (NaN: holds).
    bad |= kBadInput;
    sol.s_cmd = std::isfinite(sol.s_cmd) ? std::clamp(sol.s_cmd, p_.s_table_min, p_.s_table_max) : s;
  }
  sol.s_dot = (sol.s_cmd - s) / p_.ratio_time_constant;
  double T_P = u[in_.load_torque], J_L = u[in_.load_inertia];
  if (!std::isfinite(T_P)) {
    bad |= kBadInput;
    T_P = 0.0;
  }
  if (!(J_L >= 0.0 && std::isfinite(J_L))) {
    bad |= kBadInput;
    J_L = 0.0;
  }
  const double JD = p_.J_D + J_L;
  const double h = 1e-5;  // i'(s) by central differences on the tabulated shapes
  const double s_lo = std::max(s - h, p_.s_table_min), s_hi = std::min(s + h, p_.s_table_max);
  const double i = model_.shape_scalars(s).ratio();
  sol.di_ds = (model_.shape_scalars(s_hi).ratio() - model_.shape_scalars(s_lo).ratio()) / (s_hi - s_lo);
  sol.T_M = p_.stall_torque * (1.0 - w / p_.no_load_speed);

  // Fixed point on T_C from the quasi-static guess (losses and inertia torque are small
  // against T_C, so 4 passes settle it to well below the F_K steps of the map).
  double T_C = std::max(sol.T_M, 0.0);
  for (int k = 0; k < 4; ++k) {
    unsigned flags = bad;
    try {
      sol.belt = belt(s, w, T_C);
      sol.F_cmd = sol.belt.F_K;
      if (st_.clamping_force >= 0) apply_clamp_lag(sol.belt, x[st_.clamping_force], sol.F_cmd);
      flags |= sol.belt.flags;
    } catch (const CvtInputError&) {
      sol.belt = CvtResult{};
      sol.belt.s = s;
      sol.belt.ratio = i;
      sol.belt.omega_C = w;
      sol.belt.omega_D = i * w;
      flags |= kBadInput;
    }
    const bool modelled = belt_state_modelled(flags) && std::isfinite(sol.belt.eta_PB);
    sol.eta = modelled ? sol.belt.eta_PB : 1.0;  // outside the model: lossless belt, flagged
    sol.T_L_prim = std::isfinite(sol.belt.T_L_prim) ? sol.belt.T_L_prim : 0.0;
    sol.T_L_sec = std::isfinite(sol.belt.T_L_sec) ? sol.belt.T_L_sec : 0.0;
    const double eta = sol.eta;
    const double J = p_.J_C + i * i * JD / eta;
    sol.omega_dot = (sol.T_M - sol.T_L_prim - i * (sol.T_L_sec + T_P) / eta - JD * i * sol.di_ds * sol.s_dot * w / eta) / J;
    T_C = sol.T_M - sol.T_L_prim - p_.J_C * sol.omega_dot;
    sol.flags = flags;
  }
  sol.T_C = T_C;
  sol.omega_D_dot = i * sol.omega_dot + sol.di_ds * sol.s_dot * w;
  return sol;
}

void CvtBlock::derivatives(double t, std::span<const double> x, std::span<const double> u, std::span<double> dxdt) const {
  const Solution sol = solve(t, x, u);
  dxdt[st_.input_speed] = sol.omega_dot;
  dxdt[st_.ratio_setting] = sol.s_dot;
  if (st_.clamping_force >= 0)
    dxdt[st_.clamping_force] = ((std::isfinite(sol.F_cmd) ? sol.F_cmd : 0.0) - x[st_.clamping_force]) / p_.clamp_time_constant;
}

void CvtBlock::calc_outputs(double t, std::span<const double> x, std::span<const double> u, std::span<double> y) const {
  const Solution sol = solve(t, x, u);
  const CvtResult& r = sol.belt;
  const double w = r.omega_C;  // the speed solve() used (a NaN state: 0, flagged)
  const double i = r.ratio, wD = i * w;
  y[out_.input_speed] = std::isfinite(x[st_.input_speed]) ? x[st_.input_speed] : w;
  y[out_.output_speed] = wD;
  y[out_.ratio] = i;
  y[out_.ratio_setting] = std::isfinite(x[st_.ratio_setting]) ? x[st_.ratio_setting] : r.s;
  y[out_.motor_torque] = sol.T_M;
  y[out_.belt_torque] = sol.T_C;
  y[out_.input_torque] = sol.T_C + sol.T_L_prim;
  y[out_.output_torque] = sol.eta * sol.T_C / i - sol.T_L_sec;
  // Every output is finite, also outside the model (a NaN on the topic reads as a diverged
  // run): there η_PB is the lossless belt the equations run, η_SYS the equations' power
  // ratio (0 when the input power is not positive), and a belt number the model does not
  // give (clamping force, slip margin, stresses; the stresses at L0) is 0. The flags say which.
  const auto fin = [](double v) { return std::isfinite(v) ? v : 0.0; };
  const bool modelled = belt_state_modelled(sol.flags) && std::isfinite(r.eta_SYS);
  const double P_in = (sol.T_C + sol.T_L_prim) * w;
  y[out_.eta_PB] = sol.eta;
  y[out_.eta_SYS] = modelled ? r.eta_SYS : (P_in > 0 ? (sol.eta * sol.T_C / i - sol.T_L_sec) * wD / P_in : 0.0);
  y[out_.clamping_force] = fin(r.F_K);
  y[out_.slip_margin] = fin(r.v_KD);
  y[out_.sigma1] = fin(r.sigma[0]);
  y[out_.sigma2] = fin(r.sigma[1]);
  y[out_.sigma3] = fin(r.sigma[2]);
  y[out_.sigma4] = fin(r.sigma[3]);
  // The powers the equations dissipate: with T_D = η T_C/i the belt loses (1 − η) T_C ω_C.
  y[out_.belt_loss] = (1.0 - sol.eta) * sol.T_C * w;
  y[out_.bearing_loss] = sol.T_L_prim * w + sol.T_L_sec * wD;
  y[out_.flags] = static_cast<double>(sol.flags);
  y[out_.output_acceleration] = sol.omega_D_dot;
  y[out_.ratio_command] = sol.s_cmd;
  y[out_.motor_power] = sol.T_M * w;
  y[out_.kinetic_energy] = 0.5 * p_.J_C * w * w + 0.5 * p_.J_D * wD * wD;
  y[out_.gross_slip] = (sol.flags & kGrossSlip) ? 1.0 : 0.0;
  y[out_.torque_reversal] = (sol.flags & kTorqueReversal) ? 1.0 : 0.0;
  y[out_.outside_model] = (sol.flags & (kOutsideValidatedRange | kBadInput | kNoSolution)) ? 1.0 : 0.0;
}

std::vector<double> CvtBlock::scheduled_events(double t0, double t_end) const {
  std::vector<double> inside;
  for (const auto& point : p_.ratio_schedule)
    if (point.first > t0 && point.first < t_end) inside.push_back(point.first);
  return inside;
}

}  // namespace mechsim::models::cvt
