// ARKODE's ARKStep with the block's rhs either as the explicit part (ERK) or as the
// implicit part (DIRK, Newton on a dense direct linear solver, difference-quotient
// Jacobian). ARKStep's default tables of order 4 are used for both.
#include <cstdlib>
#include <type_traits>
#include <vector>

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "ode_backend.h"

namespace mechsim::solve::detail {
namespace {

constexpr double kRebuildOnAnyGammaChange = 1e-12;  // relative change of gamma

struct ArkodeFree {
  void operator()(void* memory) const { ARKStepFree(&memory); }
};

class ArkodeBackend final : public OdeBackend {
 public:
  ArkodeBackend(SUNContext context, const SolverOptions& options, BlockProblem& problem,
                double t0, N_Vector x0)
      : problem_(problem), implicit_(options.method == Method::arkode_dirk) {
    owned_memory_.reset(ARKStepCreate(explicit_rhs(), implicit_rhs(), t0, x0, context));
    memory_ = owned_memory_.get();
    if (memory_ == nullptr) require(-1, "ARKStepCreate", problem);
    require(ARKStepSetErrHandlerFn(memory_, &OdeBackend::keep_error_message,
                                   static_cast<OdeBackend*>(this)),
            "ARKStepSetErrHandlerFn", problem);
    require(ARKStepSStolerances(memory_, options.rtol, options.atol), "ARKStepSStolerances", problem);
    if (options.max_step > 0.0)
      require(ARKStepSetMaxStep(memory_, options.max_step), "ARKStepSetMaxStep", problem);
    require(ARKStepSetMaxNumSteps(memory_, options.max_steps_per_call), "ARKStepSetMaxNumSteps",
            problem);

    if (implicit_) {
      const auto n = static_cast<sunindextype>(problem.num_states);
      matrix_.reset(SUNDenseMatrix(n, n, context));
      if (matrix_ == nullptr) require(-1, "SUNDenseMatrix", problem);
      linear_solver_.reset(SUNLinSol_Dense(x0, matrix_.get(), context));
      if (linear_solver_ == nullptr) require(-1, "SUNLinSol_Dense", problem);
      require(ARKStepSetLinearSolver(memory_, linear_solver_.get(), matrix_.get()),
              "ARKStepSetLinearSolver", problem);
      // Rebuild the Newton matrix whenever gamma = h * a_ii changes at all. With the
      // default (rebuild only beyond a 20 % change), ARKODE 6.4 accepts a one-iteration
      // Newton solve with a stale matrix after a step cut short by the stop time: x' = -2x
      // then loses 1e-5 relative at each stop with rtol = 1e-8. The stored Jacobian is
      // reused, so this costs a small LU per step, no extra rhs evaluations.
      require(ARKStepSetDeltaGammaMax(memory_, kRebuildOnAnyGammaChange), "ARKStepSetDeltaGammaMax",
              problem);
    }
    // ARKODE asks for the user data after the linear solver has been attached.
    require(ARKStepSetUserData(memory_, &problem), "ARKStepSetUserData", problem);

    if (problem.num_event_functions > 0) {
      require(ARKStepRootInit(memory_, problem.num_event_functions, block_event_functions),
              "ARKStepRootInit", problem);
      std::vector<int> directions(static_cast<std::size_t>(problem.num_event_functions));
      for (int i = 0; i < problem.num_event_functions; ++i)
        directions[i] = static_cast<int>(problem.block.event_direction(i));
      require(ARKStepSetRootDirection(memory_, directions.data()), "ARKStepSetRootDirection",
              problem);
      require(ARKStepSetNoInactiveRootWarn(memory_), "ARKStepSetNoInactiveRootWarn", problem);
    }
  }

  ArkodeBackend(const ArkodeBackend&) = delete;
  ArkodeBackend& operator=(const ArkodeBackend&) = delete;

  Outcome evolve(double t_stop, N_Vector x, double* t_reached, int* flag) override {
    *flag = ARKStepSetStopTime(memory_, t_stop);
    if (*flag < 0) return Outcome::failed;
    *flag = ARKStepEvolve(memory_, t_stop, x, t_reached, ARK_NORMAL);
    if (*flag == ARK_ROOT_RETURN) return Outcome::root_found;
    if (*flag < 0) return Outcome::failed;
    return Outcome::reached_stop;
  }

  void reinit(double t, N_Vector x) override {
    require(ARKStepReInit(memory_, explicit_rhs(), implicit_rhs(), t, x), "ARKStepReInit", problem_);
  }

  void root_info(int* crossed) override {
    require(ARKStepGetRootInfo(memory_, crossed), "ARKStepGetRootInfo", problem_);
  }

  SolverCounters counters() const override {
    SolverCounters c;
    long explicit_evals = 0, implicit_evals = 0;
    ARKStepGetNumSteps(memory_, &c.steps);
    ARKStepGetNumRhsEvals(memory_, &explicit_evals, &implicit_evals);
    c.rhs_evals = explicit_evals + implicit_evals;
    ARKStepGetNumErrTestFails(memory_, &c.error_test_failures);
    if (implicit_) {  // the nonlinear and linear solver counters exist only with a solver
      long rhs_for_jacobian = 0;
      ARKStepGetNumLinRhsEvals(memory_, &rhs_for_jacobian);
      c.rhs_evals += rhs_for_jacobian;
      ARKStepGetNumNonlinSolvConvFails(memory_, &c.nonlinear_failures);
      ARKStepGetNumJacEvals(memory_, &c.jacobian_evals);
    }
    ARKStepGetLastStep(memory_, &c.last_step);
    c.last_order = method_order();
    return c;
  }

  std::string flag_name(int flag) const override {
    char* name = ARKStepGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
    std::string result(name != nullptr ? name : "unknown flag");
    std::free(name);
    return result;
  }

 private:
  // ARKStep picks its tables at the first step; until then the order is unknown (0).
  int method_order() const {
    ARKodeButcherTable implicit_table = nullptr;
    ARKodeButcherTable explicit_table = nullptr;
    if (ARKStepGetCurrentButcherTables(memory_, &implicit_table, &explicit_table) < 0) return 0;
    const ARKodeButcherTable table = implicit_ ? implicit_table : explicit_table;
    return table != nullptr ? table->q : 0;
  }
  ARKRhsFn explicit_rhs() const { return implicit_ ? nullptr : block_rhs; }
  ARKRhsFn implicit_rhs() const { return implicit_ ? block_rhs : nullptr; }

  BlockProblem& problem_;
  bool implicit_;
  // Owned SUNDIALS objects (see cvode_backend.cpp): solver memory freed first.
  std::unique_ptr<std::remove_pointer_t<SUNMatrix>, decltype(&SUNMatDestroy)> matrix_{nullptr,
                                                                                      &SUNMatDestroy};
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, decltype(&SUNLinSolFree)> linear_solver_{
      nullptr, &SUNLinSolFree};
  std::unique_ptr<void, ArkodeFree> owned_memory_;
  void* memory_ = nullptr;
};

}  // namespace

std::unique_ptr<OdeBackend> make_arkode_backend(SUNContext context, const SolverOptions& options,
                                                BlockProblem& problem, double t0, N_Vector x0) {
  return std::make_unique<ArkodeBackend>(context, options, problem, t0, x0);
}

}  // namespace mechsim::solve::detail
