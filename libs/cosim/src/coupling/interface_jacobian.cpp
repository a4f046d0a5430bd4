#include "mechsim/cosim/coupling/interface_jacobian.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mechsim::cosim::coupling {

std::vector<double> solve_torque_levels(const SpringDamper& law, double macro_step, const InterfacePrediction& plus,
                                        const InterfacePrediction& minus) {
  const int n = plus.levels();
  if (n < 1 || minus.levels() != n || static_cast<int>(plus.sensitivity.size()) != n ||
      static_cast<int>(minus.sensitivity.size()) != n)
    throw std::invalid_argument("interface-Jacobian coupling: the two sides predict " + std::to_string(n) + " and " +
                                std::to_string(minus.levels()) + " torque levels");
  // Bitwise: both sides took the same solved level as their assumption.
  if (!(plus.assumed_torque == minus.assumed_torque))
    throw std::invalid_argument("interface-Jacobian coupling: the two sides assume different torques (" +
                                std::to_string(plus.assumed_torque) + " and " + std::to_string(minus.assumed_torque) + " N m)");
  const double h = macro_step / n;
  const double a = law.stiffness / 2 + law.damping / h;  // weight of q_j
  const double b = law.stiffness / 2 - law.damping / h;  // weight of q_(j-1)
  std::vector<double> g(n), correction(n), levels(n);
  for (int m = 0; m < n; ++m) g[m] = plus.sensitivity[m] - minus.sensitivity[m];
  // dT_j (1 - a g_1) = a (q_pred_j + sum_(i<j) g_(j-i+1) dT_i) + b q_(j-1) - T_assumed
  const double pivot = 1.0 - a * g[0];
  if (!(pivot > 0))
    throw std::invalid_argument("interface-Jacobian coupling: the sensitivities do not resist the torque "
                                "(is the '+' side the one the torque loads?)");
  double q_previous = plus.angle - minus.angle;  // the actual twist at t_k
  for (int j = 0; j < n; ++j) {
    double q_known = plus.predicted[j] - minus.predicted[j];
    for (int i = 0; i < j; ++i) q_known += g[j - i] * correction[i];
    correction[j] = (a * q_known + b * q_previous - plus.assumed_torque) / pivot;
    levels[j] = plus.assumed_torque + correction[j];
    q_previous = q_known + g[0] * correction[j];
  }
  return levels;
}

void to_fields(const InterfacePrediction& p, std::vector<double>& fields) {
  const int n = p.levels();
  if (n < 1 || n > kMaxLevels) throw std::invalid_argument("interface-Jacobian coupling: levels must be in 1..16");
  fields.assign(3 + 2 * kMaxLevels, std::numeric_limits<double>::quiet_NaN());
  fields[0] = p.angle;
  fields[1] = p.assumed_torque;
  fields[2] = n;
  for (int j = 0; j < n; ++j) {
    fields[3 + j] = p.predicted[j];
    fields[3 + kMaxLevels + j] = p.sensitivity[j];
  }
}

InterfacePrediction from_fields(std::span<const double> fields) {
  if (fields.size() != 3 + 2 * static_cast<std::size_t>(kMaxLevels))
    throw std::invalid_argument("interface-Jacobian coupling: a CouplingPrediction sample of the wrong size");
  InterfacePrediction p;
  p.angle = fields[0];
  p.assumed_torque = fields[1];
  const double n = fields[2];
  if (!(n >= 1 && n <= kMaxLevels) || n != std::floor(n))
    throw std::invalid_argument("interface-Jacobian coupling: a CouplingPrediction sample with " + std::to_string(n) + " levels");
  for (int j = 0; j < static_cast<int>(n); ++j) {
    p.predicted.push_back(fields[3 + j]);
    p.sensitivity.push_back(fields[3 + kMaxLevels + j]);
  }
  return p;
}

InterfaceSide::InterfaceSide(models::Block& block, int torque_input, int angle_output, int levels)
    : block_(block), torque_input_(torque_input), angle_output_(angle_output), levels_(levels) {
  if (levels < 1 || levels > kMaxLevels)
    throw std::invalid_argument("interface-Jacobian coupling: levels must be in 1.." + std::to_string(kMaxLevels));
  if (torque_input < 0 || torque_input >= block.num_inputs() || angle_output < 0 || angle_output >= block.num_outputs())
    throw std::invalid_argument("interface-Jacobian coupling: no such torque input or angle output on " + block.type_name());
  for (int ft : block.outputs()[angle_output].feedthrough)
    if (ft == torque_input)
      throw std::invalid_argument("interface-Jacobian coupling: the angle output of " + block.type_name() +
                                  " depends directly on its torque input");
  u_.assign(block.num_inputs(), 0.0);
  y_.assign(block.num_outputs(), 0.0);
}

double InterfaceSide::sub_instant(double t_start, double t_end, int j) const {
  return j == levels_ ? t_end : t_start + (t_end - t_start) * j / levels_;
}

std::vector<double> InterfaceSide::sensitivity(double t, std::span<const double> x, std::span<const double> u,
                                               double h) const {
  const int n = block_.num_states();
  std::vector<double> s(levels_, 0.0);
  if (n == 0) return s;
  // Central differences of the derivatives (exact for a linear block up to rounding).
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(n + 1, n + 1);  // [[A, b], [0, 0]]
  Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(n);               // d angle / dx
  std::vector<double> xp(x.begin(), x.end()), up(u.begin(), u.end()), f_plus(n), f_minus(n), y_plus(y_), y_minus(y_);
  for (int i = 0; i <= n; ++i) {
    double& v = i < n ? xp[i] : up[torque_input_];
    const double saved = v;
    const double delta = 1e-6 * std::max(1.0, std::abs(saved));
    v = saved + delta;
    block_.derivatives(t, xp, up, f_plus);
    if (i < n) block_.calc_outputs(t, xp, up, y_plus);
    v = saved - delta;
    block_.derivatives(t, xp, up, f_minus);
    if (i < n) block_.calc_outputs(t, xp, up, y_minus);
    v = saved;
    for (int r = 0; r < n; ++r) augmented(r, i) = (f_plus[r] - f_minus[r]) / (2 * delta);
    if (i < n) c(i) = (y_plus[angle_output_] - y_minus[angle_output_]) / (2 * delta);
  }
  // exp([[A, b], [0, 0]] h) = [[Φ, Γ], [0, 1]]: Φ = e^(Ah), Γ = ∫0^h e^(As) ds b.
  const Eigen::MatrixXd e = (augmented * h).exp();
  const Eigen::MatrixXd phi = e.topLeftCorner(n, n);
  Eigen::VectorXd response = e.topRightCorner(n, 1);  // state at t + h after a unit torque on [t, t + h]
  for (int j = 0; j < levels_; ++j) {
    s[j] = c * response;
    response = phi * response;
  }
  return s;
}

InterfacePrediction InterfaceSide::predict(solve::BlockIntegrator& integrator, double t_end,
                                           const solve::InputFunction& inputs, double assumed_torque) {
  const double t0 = integrator.time();
  const std::vector<double> x0(integrator.state().begin(), integrator.state().end());
  const std::vector<double> discrete = block_.save_discrete_state();
  auto with_torque = [&](double t, std::span<double> u) {
    inputs(t, u);
    u[torque_input_] = assumed_torque;
  };
  InterfacePrediction p;
  p.assumed_torque = assumed_torque;
  with_torque(t0, u_);
  block_.calc_outputs(t0, x0, u_, y_);
  p.angle = y_[angle_output_];
  p.sensitivity = sensitivity(t0, x0, u_, (t_end - t0) / levels_);
  const solve::InputFunction f = with_torque;
  integrator.mark_discontinuity();
  for (int j = 1; j <= levels_; ++j) {
    const double t = sub_instant(t0, t_end, j);
    integrator.advance_to(t, f);
    with_torque(t, u_);
    block_.calc_outputs(t, integrator.state(), u_, y_);
    p.predicted.push_back(y_[angle_output_]);
  }
  // Back to the start: the prediction must leave no trace (state, sampled part, events).
  integrator.reset_state(t0, x0);
  block_.restore_discrete_state(discrete);
  integrator.take_events();
  block_.take_event_log();
  return p;
}

void InterfaceSide::advance(solve::BlockIntegrator& integrator, double t_end, const solve::InputFunction& inputs,
                            std::span<const double> levels) {
  if (static_cast<int>(levels.size()) != levels_)
    throw std::invalid_argument("interface-Jacobian coupling: wrong number of torque levels");
  const double t0 = integrator.time();
  for (int j = 1; j <= levels_; ++j) {
    const double torque = levels[j - 1];
    // The torque jumps at each sub-instant: the solver restarts there.
    if (j == 1 || torque != levels[j - 2]) integrator.mark_discontinuity();
    integrator.advance_to(sub_instant(t0, t_end, j), [&](double t, std::span<double> u) {
      inputs(t, u);
      u[torque_input_] = torque;
    });
  }
}

}  // namespace mechsim::cosim::coupling
