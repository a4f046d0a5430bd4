// The block seen as an ODE: the C callbacks SUNDIALS calls for the rhs and the event
// functions. Input values live in a preallocated buffer, so evaluating the rhs never
// allocates. C++ exceptions must not unwind through SUNDIALS' C frames: they are caught,
// kept, and the callback returns an unrecoverable failure; the integrator rethrows.
#pragma once

#include <exception>
#include <span>
#include <vector>

#include <sundials/sundials_nvector.h>

#include "mechsim/models/block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::solve::detail {

struct BlockProblem {
  explicit BlockProblem(models::Block& b);

  // u(t) into `inputs` (the defaults when no input function is set).
  void evaluate_inputs(double t);

  models::Block& block;
  int num_states;
  int num_event_functions;
  std::vector<double> inputs;
  std::vector<double> default_inputs;
  const InputFunction* input_function = nullptr;  // set for the duration of an advance
  std::exception_ptr callback_error;              // first exception thrown by a callback
};

// SUNDIALS-compatible callbacks (CVRhsFn / ARKRhsFn and CVRootFn / ARKRootFn signatures);
// user_data is the BlockProblem.
int block_rhs(sunrealtype t, N_Vector x, N_Vector dxdt, void* user_data);
int block_event_functions(sunrealtype t, N_Vector x, sunrealtype* g, void* user_data);

}  // namespace mechsim::solve::detail
