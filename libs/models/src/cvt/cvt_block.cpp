#include "mechsim/models/cvt/cvt_block.h"

#include <algorithm>
#include <cmath>

namespace mechsim::models::cvt {

CvtBlock::CvtBlock(CvtBlockParams params) : Block("cvt"), p_(params), model_(params.cvt) {
  if (!(p_.J_C > 0 && p_.J_D >= 0 && p_.stall_torque > 0 && p_.no_load_speed > 0 && p_.ratio_time_constant > 0))
    throw CvtInputError("cvt block: J_C, stall torque, no-load speed and ratio time constant must be > 0, J_D >= 0");
  if (!(p_.s0 >= p_.s_table_min && p_.s0 <= p_.s_table_max))
    throw CvtInputError("cvt block: the initial ratio setting must lie in the tabulated range");
  model_.tabulate_shapes(p_.s_table_min, p_.s_table_max, p_.s_table_points);

  in_.ratio_command = declare_input("ratio_command", "m", p_.s0);
  in_.load_torque = declare_input("load_torque", "N m", 0.0);
  const std::vector<int> ft{in_.load_torque};
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
  st_.input_speed = declare_state("input_speed", "rad/s");
  st_.ratio_setting = declare_state("ratio_setting", "m");
}

void CvtBlock::initial_state(double, std::span<double> x) const {
  x[st_.input_speed] = p_.omega0;
  x[st_.ratio_setting] = p_.s0;
}

CvtBlock::Solution CvtBlock::solve(std::span<const double> x, std::span<const double> u) const {
  Solution sol;
  const double w = std::max(x[st_.input_speed], 0.0);  // the motor line does not reverse the shaft
  const double s = std::clamp(x[st_.ratio_setting], p_.s_table_min, p_.s_table_max);
  const double s_cmd = std::clamp(u[in_.ratio_command], p_.s_table_min, p_.s_table_max);
  sol.s_dot = (s_cmd - x[st_.ratio_setting]) / p_.ratio_time_constant;
  const double h = 1e-5;  // i'(s) by central differences on the tabulated shapes
  const double s_lo = std::max(s - h, p_.s_table_min), s_hi = std::min(s + h, p_.s_table_max);
  sol.di_ds = (model_.shape(s_hi).ratio() - model_.shape(s_lo).ratio()) / (s_hi - s_lo);
  sol.T_M = p_.stall_torque * (1.0 - w / p_.no_load_speed);
  const double T_P = u[in_.load_torque];

  CvtOperatingPoint op;
  op.s = s;
  op.omega_C = w;
  op.clamp = p_.clamp;
  op.v_K = p_.v_K;
  op.F_K_applied = p_.F_K;
  op.level = p_.level;
  const double i = model_.shape(s).ratio();
  // Fixed point on T_C from the quasi-static guess (losses and inertia torque are small
  // against T_C, so 4 passes settle it to well below the F_K steps of the map).
  double T_C = std::max(sol.T_M, 0.0);
  for (int k = 0; k < 4; ++k) {
    op.torque = T_C;
    sol.belt = model_.evaluate(op);
    const bool modelled = belt_state_modelled(sol.belt.flags) && std::isfinite(sol.belt.eta_PB);
    const double eta = modelled ? sol.belt.eta_PB : 1.0;  // outside the model: lossless belt, flagged
    const double TLp = sol.belt.T_L_prim, TLs = sol.belt.T_L_sec;
    const double J = p_.J_C + i * i * p_.J_D / eta;
    sol.omega_dot = (sol.T_M - TLp - i * (TLs + T_P) / eta - p_.J_D * i * sol.di_ds * sol.s_dot * w / eta) / J;
    T_C = sol.T_M - TLp - p_.J_C * sol.omega_dot;
  }
  return sol;
}

void CvtBlock::derivatives(double, std::span<const double> x, std::span<const double> u, std::span<double> dxdt) const {
  const Solution sol = solve(x, u);
  dxdt[st_.input_speed] = sol.omega_dot;
  dxdt[st_.ratio_setting] = sol.s_dot;
}

void CvtBlock::calc_outputs(double, std::span<const double> x, std::span<const double> u, std::span<double> y) const {
  const Solution sol = solve(x, u);
  const CvtResult& r = sol.belt;
  y[out_.input_speed] = x[st_.input_speed];
  y[out_.output_speed] = r.omega_D;
  y[out_.ratio] = r.ratio;
  y[out_.ratio_setting] = x[st_.ratio_setting];
  y[out_.motor_torque] = sol.T_M;
  y[out_.belt_torque] = r.T_C;
  y[out_.input_torque] = r.T_1;
  y[out_.output_torque] = r.T_2;
  y[out_.eta_PB] = r.eta_PB;
  y[out_.eta_SYS] = r.eta_SYS;
  y[out_.clamping_force] = r.F_K;
  y[out_.slip_margin] = r.v_KD;
  y[out_.sigma1] = r.sigma[0];
  y[out_.sigma2] = r.sigma[1];
  y[out_.sigma3] = r.sigma[2];
  y[out_.sigma4] = r.sigma[3];
  y[out_.belt_loss] = r.P_loss_belt;
  y[out_.bearing_loss] = r.T_L_prim * r.omega_C + r.T_L_sec * r.omega_D;
  y[out_.flags] = static_cast<double>(r.flags);
}

}  // namespace mechsim::models::cvt
