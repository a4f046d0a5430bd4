#include "mechsim/cosim/coupling/interface_jacobian.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mechsim::cosim::coupling {

std::vector<double> solve_torque_levels(const SpringDamper& law, double macro_step, const InterfacePrediction& plus,
                                        const InterfacePrediction& minus) {
  std::vector<double> levels;
  solve_torque_levels(law, macro_step, plus, minus, levels);
  return levels;
}

void solve_torque_levels(const SpringDamper& law, double macro_step, const InterfacePrediction& plus,
                         const InterfacePrediction& minus, std::vector<double>& levels) {
  const int n = plus.levels();
  if (n < 1 || n > kMaxLevels || minus.levels() != n || static_cast<int>(plus.sensitivity.size()) != n ||
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
  std::array<double, kMaxLevels> g{}, correction{};
  levels.resize(n);
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
  InterfacePrediction p;
  from_fields(fields, p);
  return p;
}

void from_fields(std::span<const double> fields, InterfacePrediction& p) {
  if (fields.size() != 3 + 2 * static_cast<std::size_t>(kMaxLevels))
    throw std::invalid_argument("interface-Jacobian coupling: a CouplingPrediction sample of the wrong size");
  p.angle = fields[0];
  p.assumed_torque = fields[1];
  const double n = fields[2];
  if (!(n >= 1 && n <= kMaxLevels) || n != std::floor(n))
    throw std::invalid_argument("interface-Jacobian coupling: a CouplingPrediction sample with " + std::to_string(n) + " levels");
  p.predicted.assign(fields.begin() + 3, fields.begin() + 3 + static_cast<int>(n));
  p.sensitivity.assign(fields.begin() + 3 + kMaxLevels, fields.begin() + 3 + kMaxLevels + static_cast<int>(n));
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
  if (block.num_states() > kMaxStates)
    throw std::invalid_argument("interface-Jacobian coupling: " + block.type_name() + " has " +
                                std::to_string(block.num_states()) + " states, at most " + std::to_string(kMaxStates) +
                                " are supported on a cut");
  u_.assign(block.num_inputs(), 0.0);
  y_.assign(block.num_outputs(), 0.0);
  x0_.reserve(block.num_states());
  xp_.reserve(block.num_states());
  up_.reserve(block.num_inputs());
  f_plus_.assign(block.num_states(), 0.0);
  f_minus_.assign(block.num_states(), 0.0);
  y_plus_ = y_;
  y_minus_ = y_;
}

double InterfaceSide::sub_instant(double t_start, double t_end, int j) const {
  return j == levels_ ? t_end : t_start + (t_end - t_start) * j / levels_;
}

void InterfaceSide::sensitivity(double t, std::span<const double> x, std::span<const double> u, double h,
                                std::vector<double>& s) {
  const int n = block_.num_states();
  s.assign(levels_, 0.0);
  if (n == 0) return;
  // Fixed capacity, dynamic size: the matrices live on the stack (no allocation per step).
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxStates + 1, kMaxStates + 1>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxStates + 1, 1>;
  using RowVector = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kMaxStates>;
  // Central differences of the derivatives (exact for a linear block up to rounding).
  Matrix augmented = Matrix::Zero(n + 1, n + 1);  // [[A, b], [0, 0]]
  RowVector c = RowVector::Zero(n);               // d angle / dx
  xp_.assign(x.begin(), x.end());
  up_.assign(u.begin(), u.end());
  for (int i = 0; i <= n; ++i) {
    double& v = i < n ? xp_[i] : up_[torque_input_];
    const double saved = v;
    const double delta = 1e-6 * std::max(1.0, std::abs(saved));
    v = saved + delta;
    block_.derivatives(t, xp_, up_, f_plus_);
    if (i < n) block_.calc_outputs(t, xp_, up_, y_plus_);
    v = saved - delta;
    block_.derivatives(t, xp_, up_, f_minus_);
    if (i < n) block_.calc_outputs(t, xp_, up_, y_minus_);
    v = saved;
    for (int r = 0; r < n; ++r) augmented(r, i) = (f_plus_[r] - f_minus_[r]) / (2 * delta);
    if (i < n) c(i) = (y_plus_[angle_output_] - y_minus_[angle_output_]) / (2 * delta);
  }
  // exp([[A, b], [0, 0]] h) = [[Φ, Γ], [0, 1]]: Φ = e^(Ah), Γ = ∫0^h e^(As) ds b.
  const Matrix scaled = augmented * h;
  const Matrix e = scaled.exp();
  const Matrix phi = e.topLeftCorner(n, n);
  Vector response = e.topRightCorner(n, 1);  // state at t + h after a unit torque on [t, t + h]
  Vector next(n);
  for (int j = 0; j < levels_; ++j) {
    s[j] = c * response;
    next.noalias() = phi * response;
    response = next;
  }
}

InterfacePrediction InterfaceSide::predict(solve::BlockIntegrator& integrator, double t_end,
                                           const solve::InputFunction& inputs, double assumed_torque) {
  InterfacePrediction p;
  predict(integrator, t_end, inputs, assumed_torque, p);
  return p;
}

namespace {
// The block's inputs with the torque input overwritten: what a step integrates with. Passed
// to std::function as one pointer, which it stores without allocating.
struct InputsWithTorque {
  const solve::InputFunction* inputs;
  int torque_input;
  double torque;
  void operator()(double t, std::span<double> u) const {
    (*inputs)(t, u);
    u[torque_input] = torque;
  }
};
}  // namespace

void InterfaceSide::predict(solve::BlockIntegrator& integrator, double t_end, const solve::InputFunction& inputs,
                            double assumed_torque, InterfacePrediction& p) {
  const double t0 = integrator.time();
  x0_.assign(integrator.state().begin(), integrator.state().end());
  discrete_ = block_.save_discrete_state();
  const InputsWithTorque with_torque{&inputs, torque_input_, assumed_torque};
  p.assumed_torque = assumed_torque;
  with_torque(t0, u_);
  block_.calc_outputs(t0, x0_, u_, y_);
  p.angle = y_[angle_output_];
  sensitivity(t0, x0_, u_, (t_end - t0) / levels_, p.sensitivity);
  const solve::InputFunction f = [w = &with_torque](double t, std::span<double> u) { (*w)(t, u); };
  integrator.mark_discontinuity();
  p.predicted.clear();
  for (int j = 1; j <= levels_; ++j) {
    const double t = sub_instant(t0, t_end, j);
    integrator.advance_to(t, f);
    with_torque(t, u_);
    block_.calc_outputs(t, integrator.state(), u_, y_);
    p.predicted.push_back(y_[angle_output_]);
  }
  // Back to the start: the prediction must leave no trace (state, sampled part, events).
  integrator.reset_state(t0, x0_);
  block_.restore_discrete_state(discrete_);
  integrator.take_events();
  block_.take_event_log();
}

void InterfaceSide::advance(solve::BlockIntegrator& integrator, double t_end, const solve::InputFunction& inputs,
                            std::span<const double> levels) {
  if (static_cast<int>(levels.size()) != levels_)
    throw std::invalid_argument("interface-Jacobian coupling: wrong number of torque levels");
  const double t0 = integrator.time();
  InputsWithTorque with_torque{&inputs, torque_input_, 0.0};
  const solve::InputFunction f = [w = &with_torque](double t, std::span<double> u) { (*w)(t, u); };
  for (int j = 1; j <= levels_; ++j) {
    with_torque.torque = levels[j - 1];
    // The torque jumps at each sub-instant: the solver restarts there.
    if (j == 1 || with_torque.torque != levels[j - 2]) integrator.mark_discontinuity();
    integrator.advance_to(sub_instant(t0, t_end, j), f);
  }
}

}  // namespace mechsim::cosim::coupling
