/* The contract between a test FMU's model (tests/fmus/<name>/<name>.c) and the FMI 2 / FMI 3
 * wrappers of this folder: the model only computes, the wrappers speak FMI.
 *
 * Every variable lives in one store indexed by its value reference (unique across types, as
 * FMI 3 requires; valid for FMI 2 as well); Integer and Boolean values are held as doubles.
 * Continuous states are separate (x), and the model copies them to their variables in
 * model_outputs. */
#ifndef MECHSIM_TEST_FMU_MODEL_H
#define MECHSIM_TEST_FMU_MODEL_H

#define MODEL_MAX_VARIABLES 32
#define MODEL_MAX_STATES 4
#define MODEL_MAX_INDICATORS 4

typedef struct {
  double time;
  double value[MODEL_MAX_VARIABLES]; /* by value reference */
  double x[MODEL_MAX_STATES];
  const char* error; /* set by a hook that fails: the wrapper logs it and returns an error */
} Model;

/* Declared by each model. */
extern const int model_number_of_variables;   /* value references 0 .. n-1 */
extern const int model_number_of_states;
extern const int model_number_of_indicators;
extern const double model_max_substep;        /* the co-simulation step's RK4 substep [s] */

void model_defaults(Model* m);                 /* start values and parameters */
void model_initialize(Model* m);               /* x from the start values (exit initialization) */
void model_derivatives(const Model* m, double* dxdt);
void model_outputs(Model* m);                  /* outputs (and state variables) from x and inputs */
void model_event_indicators(const Model* m, double* z);
/* An event at m->time: a state event (an indicator crossed) or a step event. Returns 1
 * when x changed. */
int model_event(Model* m);
/* Called at the start of every co-simulation step [t, t + h] and every model-exchange
 * derivative evaluation; returns 0, or 1 with m->error set (the call then fails). */
int model_check(Model* m, double t_end);

/* Optional (a weak symbol: models without time events leave it out): the time of the next
 * time event, at which model_event is called (INFINITY: none). */
double model_next_event_time(const Model* m) __attribute__((weak));
/* model_next_event_time where the model has it, else INFINITY (solver.c). */
double next_time_event(const Model* m);

/* Co-simulation: integrates from m->time to t_end with RK4 substeps of at most
 * model_max_substep, locating state events by bisection and stopping at time events (solver.c). */
int model_advance(Model* m, double t_end);

#endif
