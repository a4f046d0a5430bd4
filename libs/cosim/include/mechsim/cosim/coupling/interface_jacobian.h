// The interface-Jacobian ("linear-implicit") coupling scheme for a stiff spring-damper cut
// between two blocks (docs/nc-loop.md, "Coupling schemes"). Pure: no transport, no YAML; the
// node stepper, an in-process runner and the unit tests use it alike.
//
// The coupling torque over macro step k -> k+1 is the unknown: N constant levels T_1..T_N on
// the sub-intervals [t_k + (j-1)h, t_k + jh], h = H/N. Each side, starting the step,
//   - predicts its interface angle at the N sub-instants with the torque it assumes (the
//     last level of the previous step; both sides know it bit for bit),
//   - states its sensitivity to the torque: the angle at sub-instant j per N m applied on
//     the first sub-interval (from the block's linearisation at t_k: finite differences of
//     its derivatives, exact for linear blocks; the response to level i is that column
//     shifted by i-1 sub-intervals),
// and publishes both with its angle at t_k (one message per side and step). Both sides then
// solve the same N x N lower-triangular system, in the same canonical order, so the two
// torques are equal bit for bit (action = reaction):
//   twist  q_j = (φ+_j - φ-_j),  q_j = q_pred_j + Σ_i g_(j-i+1) ΔT_i,  g = s+ - s-
//   law    T_j = C (q_(j-1) + q_j)/2 + d (q_j - q_(j-1))/h        (trapezoidal rule)
// The trapezoidal law makes the work of T_j on the twist equal the change of the discrete
// spring energy plus a non-negative damper loss: with exact subsystems the coupled map is
// stable for any H. Each side then integrates the step with the solved levels (for a
// nonlinear block this is one Newton step from the assumed torque, then a re-integration;
// no rollback). The "+" side is the one whose angle counts positively in the twist (the
// motor in the NC loop: its load torque is T); the "-" side receives T as a drive torque.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "mechsim/catalog/coupling/scheme.h"  // kMaxLevels
#include "mechsim/models/block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::cosim::coupling {
// Most states of a block on a cut: the linearisation works on fixed-capacity matrices
// (kMaxStates + 1 square, on the stack) so that it never allocates.
inline constexpr int kMaxStates = 15;

struct SpringDamper {
  double stiffness = 0.0;  // C [N m/rad]
  double damping = 0.0;    // d [N m s/rad]
};

// What one side publishes at the start of a step.
struct InterfacePrediction {
  double angle = 0.0;               // interface angle at t_k [rad]
  double assumed_torque = 0.0;      // torque the prediction assumes [N m]
  std::vector<double> predicted;    // angle at t_k + j h, j = 1..N [rad]
  std::vector<double> sensitivity;  // d angle(t_k + j h) / d T_1, j = 1..N [rad/(N m)]
  int levels() const { return static_cast<int>(predicted.size()); }
};

// The torque levels T_1..T_N of the step, from the "+" side's and the "-" side's
// predictions (always in this order, whichever side calls). Throws std::invalid_argument
// when the two disagree on N or on the assumed torque (they must, bit for bit).
std::vector<double> solve_torque_levels(const SpringDamper& law, double macro_step, const InterfacePrediction& plus,
                                        const InterfacePrediction& minus);
// The same into `levels` (resized to N; no allocation once it has the capacity): the form
// a node's step uses.
void solve_torque_levels(const SpringDamper& law, double macro_step, const InterfacePrediction& plus,
                         const InterfacePrediction& minus, std::vector<double>& levels);

// The CouplingPrediction fields (transport/topic_types.cpp order) and back.
void to_fields(const InterfacePrediction& p, std::vector<double>& fields);
InterfacePrediction from_fields(std::span<const double> fields);
void from_fields(std::span<const double> fields, InterfacePrediction& out);  // reuses out's buffers

// One side of the cut: its block with a torque input and an angle output. The block's
// torque input receives T as it is (the NC motor's load_torque, the spindle's drive_torque).
class InterfaceSide {
 public:
  // levels in 1..kMaxLevels. The angle output must not depend on the torque directly
  // (no feedthrough); throws std::invalid_argument otherwise.
  InterfaceSide(models::Block& block, int torque_input, int angle_output, int levels);

  // Prediction for the step [integrator.time(), t_end], with the block's other inputs from
  // `inputs` (its torque input is overwritten). Leaves the integrator at its start state.
  InterfacePrediction predict(solve::BlockIntegrator& integrator, double t_end, const solve::InputFunction& inputs,
                              double assumed_torque);
  // The same into `out`, reusing its buffers: allocation-free in a node's steady state.
  void predict(solve::BlockIntegrator& integrator, double t_end, const solve::InputFunction& inputs, double assumed_torque,
               InterfacePrediction& out);
  // Integrates the step with the solved levels (piecewise constant, a restart at each
  // sub-instant where the torque jumps).
  void advance(solve::BlockIntegrator& integrator, double t_end, const solve::InputFunction& inputs,
               std::span<const double> levels);

  int levels() const { return levels_; }
  int torque_input() const { return torque_input_; }

 private:
  double sub_instant(double t_start, double t_end, int j) const;
  // Linearisation at (t, x, u): s_j for j = 1..N, over sub-intervals of length h, into s.
  void sensitivity(double t, std::span<const double> x, std::span<const double> u, double h, std::vector<double>& s);

  models::Block& block_;
  int torque_input_, angle_output_, levels_;
  std::vector<double> u_, y_;
  // Buffers of predict() and sensitivity(), sized once: a step must not allocate.
  std::vector<double> x0_, discrete_, xp_, up_, f_plus_, f_minus_, y_plus_, y_minus_;
};

}  // namespace mechsim::cosim::coupling
