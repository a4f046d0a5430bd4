#include "block_problem.h"

#include <algorithm>
#include <cmath>

#include <nvector/nvector_serial.h>

namespace mechsim::solve::detail {

BlockProblem::BlockProblem(models::Block& b)
    : block(b),
      num_states(b.num_states()),
      num_event_functions(b.num_event_functions()),
      inputs(b.default_inputs()),
      default_inputs(b.default_inputs()) {}

void BlockProblem::evaluate_inputs(double t) {
  if (input_function != nullptr && *input_function)
    (*input_function)(t, inputs);
  else
    std::copy(default_inputs.begin(), default_inputs.end(), inputs.begin());
}

namespace {
// SUNDIALS convention: 0 ok, > 0 recoverable (the solver retries with a smaller step),
// < 0 unrecoverable.
constexpr int kOk = 0;
constexpr int kRecoverable = 1;
constexpr int kUnrecoverable = -1;
}  // namespace

int block_rhs(sunrealtype t, N_Vector x, N_Vector dxdt, void* user_data) {
  auto& p = *static_cast<BlockProblem*>(user_data);
  const auto n = static_cast<std::size_t>(p.num_states);
  std::span<double> dx(N_VGetArrayPointer(dxdt), n);
  try {
    p.evaluate_inputs(t);
    p.block.derivatives(t, std::span<const double>(N_VGetArrayPointer(x), n), p.inputs, dx);
  } catch (...) {
    if (!p.callback_error) p.callback_error = std::current_exception();
    return kUnrecoverable;
  }
  // A non-finite derivative usually means a trial state outside the model's domain
  // (e.g. a too long step): let the solver retry with a smaller step.
  for (double d : dx)
    if (!std::isfinite(d)) return kRecoverable;
  return kOk;
}

int block_event_functions(sunrealtype t, N_Vector x, sunrealtype* g, void* user_data) {
  auto& p = *static_cast<BlockProblem*>(user_data);
  const auto n = static_cast<std::size_t>(p.num_states);
  try {
    p.evaluate_inputs(t);
    p.block.event_functions(t, std::span<const double>(N_VGetArrayPointer(x), n), p.inputs,
                            std::span<double>(g, static_cast<std::size_t>(p.num_event_functions)));
  } catch (...) {
    if (!p.callback_error) p.callback_error = std::current_exception();
    return kUnrecoverable;
  }
  return kOk;
}

}  // namespace mechsim::solve::detail
