// Settings, counters and event records of a BlockIntegrator.
#pragma once

namespace mechsim::solve {

enum class Method {
  cvode_bdf,    // CVODE variable-order BDF (orders 1-5), Newton + dense LU: stiff problems
  cvode_adams,  // CVODE Adams-Moulton (orders 1-12), Newton + dense LU: smooth non-stiff problems
  arkode_erk,   // ARKODE ARKStep explicit RK, default 4th-order table: cheap non-stiff steps
  arkode_dirk,  // ARKODE ARKStep diagonally implicit RK, default 4th-order table, Newton + dense LU
};

struct SolverOptions {
  Method method = Method::cvode_bdf;
  double rtol = 1e-6;
  double atol = 1e-9;                // scalar absolute tolerance, in the states' SI units
  double max_step = 0.0;             // 0 = unlimited
  long max_steps_per_call = 500000;  // per internal solver call (i.e. between two stops)
};

// Cumulative over the integrator's life, across every restart.
struct SolverStats {
  long steps = 0;
  long rhs_evals = 0;             // including those spent on finite-difference Jacobians
  long error_test_failures = 0;
  long nonlinear_failures = 0;    // nonlinear solver convergence failures
  long jacobian_evals = 0;
  long roots_found = 0;           // event crossings reported (one per EventRecord)
  long restarts = 0;              // re-initialisations after the first initialisation
  double last_step = 0.0;
  int last_order = 0;             // CVODE: current order; ARKODE: order of the RK table
};

struct EventRecord {
  double t;
  int function_index;
  int direction;  // +1 rising, -1 falling
};

}  // namespace mechsim::solve
