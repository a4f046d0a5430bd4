// Integrates one models::Block in time with SUNDIALS, between exchange points.
//
// The owner (a node or the monolithic composer) calls advance_to(t_next, u) once per macro
// step; the integrator stops exactly at t_next, locates the block's zero crossings on the
// way, and calls the block's sampled update on its sample grid t0 + j*Ts.
//
//   - Zero-state blocks: time just moves; discrete_update still runs on its grid. Event
//     functions on such a block are not supported (the constructor refuses them), since
//     there is no solver to locate their roots.
//   - Restarts: a restart re-initialises the solver (CVodeReInit / ARKStepReInit), which
//     drops the multistep history and re-estimates the first step. It happens after
//     mark_discontinuity(), reset_state(), a handled event that changed the state, and
//     every discrete_update (its result is usually held by the derivatives, i.e. a jump).
//   - Chattering guard: events less than kEventTimeResolution (relative to max(1, |t|))
//     apart count as simultaneous. After kMaxSimultaneousEvents simultaneous handled
//     events, further crossings at that instant are let pass: handle_events is not called
//     and nothing is recorded, so the solver simply continues.
//   - Errors: any solver failure throws std::runtime_error naming the SUNDIALS flag and
//     the block type; an exception thrown by the block inside a callback is reported the
//     same way with its message. The integrator is then only usable after reset_state().
//
// Not thread-safe; one integrator per block; the block must outlive the integrator.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "mechsim/models/block.h"
#include "mechsim/solve/solver_options.h"

namespace mechsim::solve {

// Fills u(t) (all block inputs, in port order). An empty function means default inputs.
using InputFunction = std::function<void(double t, std::span<double> u)>;

class BlockIntegrator {
 public:
  static constexpr int kMaxSimultaneousEvents = 5;
  static constexpr double kEventTimeResolution = 1e-10;  // s, relative to max(1, |t|)

  BlockIntegrator(models::Block& block, SolverOptions options, double t0, std::span<const double> x0);
  ~BlockIntegrator();
  BlockIntegrator(BlockIntegrator&&) noexcept;
  BlockIntegrator& operator=(BlockIntegrator&&) noexcept;

  // Integrates from time() to t_end exactly (a stop time, never past it) with inputs u(t).
  // Each zero crossing calls block.handle_events(...), and if it returns true the solver
  // restarts from the new state. A sampled block (sample_time() > 0) gets discrete_update
  // at every grid instant reached, before integrating past it: the instant t0 at the first
  // call, then every t0 + j*Ts in (time(), t_end] (so one landing on t_end is done before
  // returning, with u(t_end)). Throws std::invalid_argument if t_end < time().
  void advance_to(double t_end, const InputFunction& u);

  // Inputs are discontinuous at the current time: restart at the next advance.
  void mark_discontinuity();

  // Replace the state (e.g. after a coupling correction); implies a restart. If t differs
  // from time(), the sample grid resumes at the first instant strictly after t.
  void reset_state(double t, std::span<const double> x);

  double time() const;
  std::span<const double> state() const;
  const SolverStats& stats() const;
  std::vector<EventRecord> take_events();  // events since the last call

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A sampled block's grid: instant j is t0 + j Ts, computed from j (never accumulated), the
// same double for the integrator that samples there and for a node that lands an adaptive
// step on it (cosim::NodeStepper).
inline double sample_instant(double t0, double ts, long long j) { return t0 + static_cast<double>(j) * ts; }
// The smallest j with sample_instant(t0, ts, j) > at (at >= t0).
long long first_sample_after(double t0, double ts, double at);

}  // namespace mechsim::solve
