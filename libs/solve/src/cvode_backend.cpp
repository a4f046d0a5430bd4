// CVODE: BDF or Adams-Moulton, both with a Newton iteration on a dense direct linear
// solver and SUNDIALS' difference-quotient Jacobian (blocks provide no Jacobian). Newton
// rather than fixed-point for Adams too: it tolerates mildly stiff blocks at little cost
// for the small state vectors of our blocks.
#include <cstdlib>
#include <type_traits>
#include <vector>

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "ode_backend.h"

namespace mechsim::solve::detail {
namespace {

struct CvodeFree {
  void operator()(void* memory) const { CVodeFree(&memory); }
};

class CvodeBackend final : public OdeBackend {
 public:
  CvodeBackend(SUNContext context, const SolverOptions& options, BlockProblem& problem,
               double t0, N_Vector x0)
      : problem_(problem) {
    owned_memory_.reset(
        CVodeCreate(options.method == Method::cvode_bdf ? CV_BDF : CV_ADAMS, context));
    memory_ = owned_memory_.get();
    if (memory_ == nullptr) require(-1, "CVodeCreate", problem);
    require(CVodeSetErrHandlerFn(memory_, &OdeBackend::keep_error_message,
                                 static_cast<OdeBackend*>(this)),
            "CVodeSetErrHandlerFn", problem);
    require(CVodeInit(memory_, block_rhs, t0, x0), "CVodeInit", problem);
    require(CVodeSetUserData(memory_, &problem), "CVodeSetUserData", problem);
    require(CVodeSStolerances(memory_, options.rtol, options.atol), "CVodeSStolerances", problem);
    if (options.max_step > 0.0)
      require(CVodeSetMaxStep(memory_, options.max_step), "CVodeSetMaxStep", problem);
    require(CVodeSetMaxNumSteps(memory_, options.max_steps_per_call), "CVodeSetMaxNumSteps", problem);

    const auto n = static_cast<sunindextype>(problem.num_states);
    matrix_.reset(SUNDenseMatrix(n, n, context));
    if (matrix_ == nullptr) require(-1, "SUNDenseMatrix", problem);
    linear_solver_.reset(SUNLinSol_Dense(x0, matrix_.get(), context));
    if (linear_solver_ == nullptr) require(-1, "SUNLinSol_Dense", problem);
    require(CVodeSetLinearSolver(memory_, linear_solver_.get(), matrix_.get()),
            "CVodeSetLinearSolver", problem);

    if (problem.num_event_functions > 0) {
      require(CVodeRootInit(memory_, problem.num_event_functions, block_event_functions),
              "CVodeRootInit", problem);
      std::vector<int> directions(static_cast<std::size_t>(problem.num_event_functions));
      for (int i = 0; i < problem.num_event_functions; ++i)
        directions[i] = static_cast<int>(problem.block.event_direction(i));
      require(CVodeSetRootDirection(memory_, directions.data()), "CVodeSetRootDirection", problem);
      // After an event the new state often sits exactly on g = 0: expected, not a warning.
      require(CVodeSetNoInactiveRootWarn(memory_), "CVodeSetNoInactiveRootWarn", problem);
    }
  }

  CvodeBackend(const CvodeBackend&) = delete;
  CvodeBackend& operator=(const CvodeBackend&) = delete;

  Outcome evolve(double t_stop, N_Vector x, double* t_reached, int* flag) override {
    *flag = CVodeSetStopTime(memory_, t_stop);
    if (*flag < 0) return Outcome::failed;
    *flag = CVode(memory_, t_stop, x, t_reached, CV_NORMAL);
    if (*flag == CV_ROOT_RETURN) return Outcome::root_found;
    if (*flag < 0) return Outcome::failed;
    return Outcome::reached_stop;
  }

  void reinit(double t, N_Vector x) override {
    require(CVodeReInit(memory_, t, x), "CVodeReInit", problem_);
  }

  void root_info(int* crossed) override {
    require(CVodeGetRootInfo(memory_, crossed), "CVodeGetRootInfo", problem_);
  }

  SolverCounters counters() const override {
    SolverCounters c;
    long rhs_for_jacobian = 0;
    CVodeGetNumSteps(memory_, &c.steps);
    CVodeGetNumRhsEvals(memory_, &c.rhs_evals);
    CVodeGetNumLinRhsEvals(memory_, &rhs_for_jacobian);
    c.rhs_evals += rhs_for_jacobian;
    CVodeGetNumErrTestFails(memory_, &c.error_test_failures);
    CVodeGetNumNonlinSolvConvFails(memory_, &c.nonlinear_failures);
    CVodeGetNumJacEvals(memory_, &c.jacobian_evals);
    CVodeGetLastStep(memory_, &c.last_step);
    CVodeGetLastOrder(memory_, &c.last_order);
    return c;
  }

  std::string flag_name(int flag) const override {
    char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
    std::string result(name != nullptr ? name : "unknown flag");
    std::free(name);
    return result;
  }

 private:
  BlockProblem& problem_;
  // Owned SUNDIALS objects; members so that a throwing constructor frees them too. The
  // solver memory is declared last, so it is freed before the linear solver it uses.
  std::unique_ptr<std::remove_pointer_t<SUNMatrix>, decltype(&SUNMatDestroy)> matrix_{nullptr,
                                                                                      &SUNMatDestroy};
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, decltype(&SUNLinSolFree)> linear_solver_{
      nullptr, &SUNLinSolFree};
  std::unique_ptr<void, CvodeFree> owned_memory_;
  void* memory_ = nullptr;
};

}  // namespace

std::unique_ptr<OdeBackend> make_cvode_backend(SUNContext context, const SolverOptions& options,
                                               BlockProblem& problem, double t0, N_Vector x0) {
  return std::make_unique<CvodeBackend>(context, options, problem, t0, x0);
}

}  // namespace mechsim::solve::detail
