// What BlockIntegrator needs from a SUNDIALS integrator; one implementation for CVODE,
// one for ARKODE's ARKStep. Owns the solver memory, the dense matrix and linear solver.
#pragma once

#include <memory>
#include <string>

#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

#include "block_problem.h"
#include "mechsim/solve/solver_options.h"

namespace mechsim::solve::detail {

// Raw solver counters since the last (re)initialisation, as far as the solver keeps them.
struct SolverCounters {
  long steps = 0;
  long rhs_evals = 0;
  long error_test_failures = 0;
  long nonlinear_failures = 0;
  long jacobian_evals = 0;
  double last_step = 0.0;
  int last_order = 0;
};

class OdeBackend {
 public:
  enum class Outcome { reached_stop, root_found, failed };

  virtual ~OdeBackend() = default;
  // Integrates towards t_stop without passing it; x receives the solution at *t_reached.
  // On failure, *flag holds the SUNDIALS return flag.
  virtual Outcome evolve(double t_stop, N_Vector x, double* t_reached, int* flag) = 0;
  // Fresh start at (t, x): multistep history and step size estimate dropped.
  virtual void reinit(double t, N_Vector x) = 0;
  // After Outcome::root_found: +1 / -1 / 0 per event function.
  virtual void root_info(int* crossed) = 0;
  virtual SolverCounters counters() const = 0;
  virtual std::string flag_name(int flag) const = 0;
  // Last error message the solver emitted (empty if none).
  const std::string& last_message() const { return last_message_; }

 protected:
  // SUNDIALS error handler: keep the message instead of printing it (the integrator turns
  // it into an exception). Warnings are dropped.
  static void keep_error_message(int error_code, const char* module, const char* function,
                                 char* msg, void* backend);
  // Set-up calls that must not fail: throw std::runtime_error naming the call and the block.
  void require(int flag, const char* call, const BlockProblem& problem) const;
  std::string last_message_;
};

std::unique_ptr<OdeBackend> make_cvode_backend(SUNContext context, const SolverOptions& options,
                                               BlockProblem& problem, double t0, N_Vector x0);
std::unique_ptr<OdeBackend> make_arkode_backend(SUNContext context, const SolverOptions& options,
                                                BlockProblem& problem, double t0, N_Vector x0);

}  // namespace mechsim::solve::detail
