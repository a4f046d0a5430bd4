// One inbound edge of a node at run time: the samples received from the partner, keyed by
// step, and the reconstruction of the partner's values between exchanges (the design's
// time section):
//  - Jacobi edge, step k -> k+1 needs the partner's step-k sample; inside the step the
//    input is held (ZOH), extrapolated linearly from steps k-1 and k, or quadratically from
//    k-2, k-1 and k (with fewer samples at the start: hold at k = 0, linear at k = 1; on
//    an adaptive grid likewise after an event: no sample before it is used);
//  - Gauss-Seidel edge needs the step-(k+1) sample; inside the step the input is
//    interpolated between steps k and k+1.
// Pure logic (no transport), so the protocol is unit-tested without DDS.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/step_grid.h"

namespace mechsim::cosim {

class InputChannel {
 public:
  // Sample k is the partner's value at grid->time(k); on a grid that is not uniform the
  // reconstruction uses those instants (divided differences), on a uniform one it is the
  // same arithmetic as ever (bit-identical runs across versions).
  InputChannel(config::EdgeOrder order, config::Reconstruction reconstruction, std::shared_ptr<const StepGrid> grid);

  // Stores a received sample (a copy). Samples may arrive in any order; a duplicate (the
  // redundant copy) is ignored when it carries the same values, and refused (false) when
  // it does not: two different samples for one step mean a foreign writer. Allocation-free
  // in the steady state: the map nodes of discarded samples are kept and reused (a
  // real-time step must not allocate, docs/realtime.md).
  bool add(std::uint64_t step, const std::vector<double>& values);
  // True when the channel holds what stepping k -> k+1 needs.
  bool ready_for_step(std::uint64_t k) const;
  // True when it holds what the initial outputs (step 0) need: only Gauss-Seidel edges
  // wait; a Jacobi edge uses initial values at step 0.
  bool ready_for_initial() const;
  // Partner values reconstructed at time t in step k -> k+1 (t in [t_k, t_k+1]);
  // requires ready_for_step(k).
  void values_at(double t, std::uint64_t k, std::vector<double>& out) const;
  // Partner values at the end of step k -> k+1 (t_k+1), for the step-(k+1) outputs:
  // exactly the step-(k+1) sample on a Gauss-Seidel edge, the held or extrapolated value
  // on a Jacobi edge. Same as values_at(t_k+1, k) but free of rounding in the fraction.
  void values_at_step_end(std::uint64_t k, std::vector<double>& out) const;
  // Partner values for the initial outputs at t0: the step-0 sample on a Gauss-Seidel
  // edge, the initial values on a Jacobi edge (the delayed edge that breaks a loop).
  void initial_values_at(std::vector<double>& out) const;
  void initial_values(std::span<const double> initial) { initial_.assign(initial.begin(), initial.end()); }
  // Drops samples no longer needed once the node is at step k.
  void discard_before(std::uint64_t k);
  std::uint64_t newest_step() const { return samples_.empty() ? 0 : samples_.rbegin()->first; }
  bool empty() const { return samples_.empty(); }
  config::EdgeOrder order() const { return order_; }
  // The samples held, by step (the linear analysis of the macro-step map reads and
  // perturbs them: tools/bench/stability.cpp).
  std::map<std::uint64_t, std::vector<double>>& held_samples() { return samples_; }
  const std::map<std::uint64_t, std::vector<double>>& held_samples() const { return samples_; }

 private:
  const std::vector<double>* find(std::uint64_t step) const;
  // Jacobi reconstruction at time t of step k -> k+1; s is the fraction of the step
  // (s = 1: t_k+1), what a uniform grid's arithmetic uses.
  void extrapolate(double t, double s, std::uint64_t k, std::vector<double>& out) const;
  config::EdgeOrder order_;
  config::Reconstruction reconstruction_;
  std::shared_ptr<const StepGrid> grid_;
  std::map<std::uint64_t, std::vector<double>> samples_;
  std::vector<std::map<std::uint64_t, std::vector<double>>::node_type> spare_;  // discarded, for reuse
  std::vector<double> initial_;
};

}  // namespace mechsim::cosim
