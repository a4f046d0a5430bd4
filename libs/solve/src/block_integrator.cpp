#include "mechsim/solve/block_integrator.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "block_problem.h"
#include "ode_backend.h"
#include "stateless_events.h"

namespace mechsim::solve {

namespace {

const char* method_name(Method m) {
  switch (m) {
    case Method::cvode_bdf: return "cvode_bdf";
    case Method::cvode_adams: return "cvode_adams";
    case Method::arkode_erk: return "arkode_erk";
    case Method::arkode_dirk: return "arkode_dirk";
  }
  return "unknown method";
}

// Two times closer than a few ulps are the same time: integrating across such a gap is
// both pointless and refused by SUNDIALS ("tout too close to t0").
bool same_time(double a, double b) {
  return std::abs(a - b) <= 4.0 * DBL_EPSILON * std::max(std::abs(a), std::abs(b));
}

struct ContextFree {
  void operator()(SUNContext context) const { SUNContext_Free(&context); }
};
struct VectorFree {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};

}  // namespace

struct BlockIntegrator::Impl {
  Impl(models::Block& block, SolverOptions opts, double t0, std::span<const double> x0);

  std::span<double> x() {
    return {vector ? N_VGetArrayPointer(vector.get()) : nullptr,
            static_cast<std::size_t>(problem.num_states)};
  }

  // --- sampled part: instants t0 + j * Ts, j = next_sample, next_sample + 1, ...
  bool sampled() const { return sample_period > 0.0; }
  double sample_instant(long long j) const { return solve::sample_instant(sample_origin, sample_period, j); }
  // An instant within this of t counts as reached: absorbs rounding in t0 + j*Ts and in the
  // caller's exchange times, yet stays far below any physically meaningful interval.
  double sample_slack(double at) const { return 1e-9 * sample_period + 8.0 * DBL_EPSILON * std::abs(at); }
  void run_due_samples();
  void resume_samples_after(double at);

  void integrate_to(double target);
  void handle_root();
  void step_stateless_events_to(double target);
  void dispatch_events();  // the crossings in `crossed` at t, to the block
  void restart();
  void refresh_stats();
  [[noreturn]] void fail(int flag);

  detail::BlockProblem problem;
  SolverOptions options;
  // Declaration order = reverse destruction order: the context outlives what uses it.
  std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree> context;
  std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree> vector;
  std::unique_ptr<detail::OdeBackend> backend;

  double t;
  bool restart_pending = false;

  double sample_period;
  double sample_origin;
  long long next_sample = 0;

  // stats = counters accumulated before the last restart + (solver counters - offset).
  SolverStats stats;
  detail::SolverCounters accumulated;
  detail::SolverCounters offset;

  std::vector<int> crossed;
  std::vector<EventRecord> events;
  double last_event_time = -std::numeric_limits<double>::infinity();
  int events_at_this_time = 0;
};

BlockIntegrator::Impl::Impl(models::Block& block, SolverOptions opts, double t0,
                            std::span<const double> x0)
    : problem(block),
      options(opts),
      t(t0),
      sample_period(block.sample_time()),
      sample_origin(t0),
      crossed(static_cast<std::size_t>(block.num_event_functions()), 0) {
  const std::string who = "BlockIntegrator(" + block.type_name() + "): ";
  if (x0.size() != static_cast<std::size_t>(problem.num_states))
    throw std::invalid_argument(who + "x0 has " + std::to_string(x0.size()) + " entries, the block " +
                                std::to_string(problem.num_states) + " states");
  if (!(options.rtol > 0.0) || !(options.atol >= 0.0) || !(options.max_step >= 0.0) ||
      options.max_steps_per_call <= 0)
    throw std::invalid_argument(who + "invalid solver options");
  if (problem.num_states == 0) return;  // no solver: time just moves

  SUNContext raw_context = nullptr;
  if (SUNContext_Create(nullptr, &raw_context) != 0)
    throw std::runtime_error(who + "SUNContext_Create failed");
  context.reset(raw_context);
  vector.reset(N_VNew_Serial(static_cast<sunindextype>(problem.num_states), context.get()));
  if (!vector) throw std::runtime_error(who + "N_VNew_Serial failed");
  std::copy(x0.begin(), x0.end(), x().begin());

  switch (options.method) {
    case Method::cvode_bdf:
    case Method::cvode_adams:
      backend = detail::make_cvode_backend(context.get(), options, problem, t0, vector.get());
      break;
    case Method::arkode_erk:
    case Method::arkode_dirk:
      backend = detail::make_arkode_backend(context.get(), options, problem, t0, vector.get());
      break;
  }
}

void BlockIntegrator::Impl::run_due_samples() {
  if (!sampled()) return;
  while (sample_instant(next_sample) <= t + sample_slack(t)) {
    problem.evaluate_inputs(t);
    problem.block.discrete_update(sample_instant(next_sample), x(), problem.inputs);
    ++next_sample;
    // The update usually changes what the derivatives hold: a jump for the solver.
    restart_pending = true;
  }
}

void BlockIntegrator::Impl::resume_samples_after(double at) {
  if (!sampled()) return;
  next_sample = first_sample_after(sample_origin, sample_period, at + sample_slack(at));
}

long long first_sample_after(double t0, double ts, double at) {
  // The division's guess may be one off either way; the instants themselves decide.
  auto j = static_cast<long long>(std::floor((at - t0) / ts));
  while (j > 0 && sample_instant(t0, ts, j - 1) > at) --j;
  while (sample_instant(t0, ts, j) <= at) ++j;
  return j;
}

void BlockIntegrator::Impl::integrate_to(double target) {
  if (problem.num_states == 0 && problem.num_event_functions > 0) return step_stateless_events_to(target);
  if (problem.num_states == 0 || same_time(t, target)) {
    t = target;
    return;
  }
  while (true) {
    if (restart_pending) restart();
    double t_reached = t;
    int flag = 0;
    const auto outcome = backend->evolve(target, vector.get(), &t_reached, &flag);
    refresh_stats();
    if (outcome == detail::OdeBackend::Outcome::failed) fail(flag);
    if (outcome == detail::OdeBackend::Outcome::reached_stop) {
      t = target;  // the stop time is hit exactly; do not let rounding move it
      return;
    }
    t = t_reached;
    handle_root();
    if (same_time(t, target)) {
      t = target;
      return;
    }
  }
}

// No solver: time moves from crossing to crossing, each located by bisection (stateless_events.h).
void BlockIntegrator::Impl::step_stateless_events_to(double target) {
  const auto g_at = [this](double at, std::span<double> g) {
    problem.evaluate_inputs(at);
    problem.block.event_functions(at, x(), problem.inputs, g);
  };
  std::vector<models::Crossing> directions;
  for (int i = 0; i < problem.num_event_functions; ++i) directions.push_back(problem.block.event_direction(i));
  while (!same_time(t, target)) {
    const double resolution = kEventTimeResolution * std::max(1.0, std::abs(target));
    const auto at = detail::first_stateless_crossing(g_at, directions, t, target, resolution, crossed);
    if (!at) break;
    t = *at;
    dispatch_events();
  }
  t = target;
}

void BlockIntegrator::Impl::handle_root() {
  backend->root_info(crossed.data());
  dispatch_events();
}

void BlockIntegrator::Impl::dispatch_events() {
  // Chattering guard: the same instant (within the resolution) counts the handled events.
  if (std::abs(t - last_event_time) <= kEventTimeResolution * std::max(1.0, std::abs(t)))
    ++events_at_this_time;
  else
    events_at_this_time = 1;
  last_event_time = t;
  if (events_at_this_time > kMaxSimultaneousEvents) return;  // let it pass

  for (std::size_t i = 0; i < crossed.size(); ++i) {
    if (crossed[i] == 0) continue;
    events.push_back({t, static_cast<int>(i), crossed[i] > 0 ? 1 : -1});
    ++stats.roots_found;
  }
  problem.evaluate_inputs(t);
  if (problem.block.handle_events(t, x(), problem.inputs, crossed) && backend) restart_pending = true;
}

void BlockIntegrator::Impl::restart() {
  refresh_stats();
  accumulated = {stats.steps, stats.rhs_evals, stats.error_test_failures, stats.nonlinear_failures,
                 stats.jacobian_evals, stats.last_step, stats.last_order};
  backend->reinit(t, vector.get());
  // Whether a ReInit zeroes the solver's counters differs between solvers and versions:
  // count from whatever they read now.
  offset = backend->counters();
  ++stats.restarts;
  restart_pending = false;
}

void BlockIntegrator::Impl::refresh_stats() {
  const detail::SolverCounters now = backend->counters();
  stats.steps = accumulated.steps + now.steps - offset.steps;
  stats.rhs_evals = accumulated.rhs_evals + now.rhs_evals - offset.rhs_evals;
  stats.error_test_failures =
      accumulated.error_test_failures + now.error_test_failures - offset.error_test_failures;
  stats.nonlinear_failures =
      accumulated.nonlinear_failures + now.nonlinear_failures - offset.nonlinear_failures;
  stats.jacobian_evals = accumulated.jacobian_evals + now.jacobian_evals - offset.jacobian_evals;
  if (now.steps != offset.steps) {  // keep the last values until the restarted solver steps
    stats.last_step = now.last_step;
    stats.last_order = now.last_order;
  }
}

void BlockIntegrator::Impl::fail(int flag) {
  restart_pending = true;  // the solver's history is unusable; reset_state() starts afresh
  std::ostringstream message;
  message.precision(17);
  message << "mechsim::solve: integrating block '" << problem.block.type_name() << "' with "
          << method_name(options.method) << " failed at t = " << t << ": "
          << backend->flag_name(flag);
  if (problem.callback_error) {
    try {
      std::rethrow_exception(std::exchange(problem.callback_error, nullptr));
    } catch (const std::exception& e) {
      message << " (the block threw: " << e.what() << ")";
    } catch (...) {
      message << " (the block threw a non-standard exception)";
    }
  } else if (!backend->last_message().empty()) {
    message << " (" << backend->last_message() << ")";
  }
  throw std::runtime_error(message.str());
}

// --- public interface -------------------------------------------------------------------

BlockIntegrator::BlockIntegrator(models::Block& block, SolverOptions options, double t0,
                                 std::span<const double> x0)
    : impl_(std::make_unique<Impl>(block, options, t0, x0)) {}

BlockIntegrator::~BlockIntegrator() = default;
BlockIntegrator::BlockIntegrator(BlockIntegrator&&) noexcept = default;
BlockIntegrator& BlockIntegrator::operator=(BlockIntegrator&&) noexcept = default;

void BlockIntegrator::advance_to(double t_end, const InputFunction& u) {
  Impl& s = *impl_;
  if (!(t_end >= s.t))
    throw std::invalid_argument("BlockIntegrator(" + s.problem.block.type_name() +
                                "): advance_to a time before time()");
  // The input function is only borrowed for this call.
  struct InputScope {
    detail::BlockProblem& p;
    ~InputScope() { p.input_function = nullptr; }
  } scope{s.problem};
  s.problem.input_function = &u;

  while (true) {
    s.run_due_samples();
    if (s.t >= t_end) break;
    double target = t_end;
    if (s.sampled()) target = std::min(target, s.sample_instant(s.next_sample));
    s.integrate_to(target);
  }
}

void BlockIntegrator::mark_discontinuity() { impl_->restart_pending = true; }

void BlockIntegrator::reset_state(double t, std::span<const double> x) {
  Impl& s = *impl_;
  if (x.size() != static_cast<std::size_t>(s.problem.num_states))
    throw std::invalid_argument("BlockIntegrator(" + s.problem.block.type_name() +
                                "): reset_state with a wrong state size");
  std::copy(x.begin(), x.end(), s.x().begin());
  if (t != s.t) {
    s.resume_samples_after(t);
    s.last_event_time = -std::numeric_limits<double>::infinity();
    s.events_at_this_time = 0;
  }
  s.t = t;
  s.restart_pending = true;
}

double BlockIntegrator::time() const { return impl_->t; }

std::span<const double> BlockIntegrator::state() const { return impl_->x(); }

const SolverStats& BlockIntegrator::stats() const { return impl_->stats; }

std::vector<EventRecord> BlockIntegrator::take_events() { return std::exchange(impl_->events, {}); }

}  // namespace mechsim::solve
