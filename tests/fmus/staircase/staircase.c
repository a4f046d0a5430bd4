/* A staircase without continuous states: a counter n that steps up by one at every
 * t_k = t0 + k * period (k >= 1), scheduled as the FMU's next time event, and its output
 * y = height * n. With t0 = 0: n(t) = floor(t / period), right-continuous (the value after
 * the event at t_k is n = k). A model-exchange importer must run its discrete update at
 * each event time with no integrator to find them (issue 38 item 6). Value references:
 * 0 y [m] output, 1 count (Integer output), 2 period [s], 3 height [m] parameters,
 * 4 next_step [s] local; 5 the start time (internal, not in the description). No inputs. */
#include <math.h>

#include "model.h"

enum { Y, COUNT, PERIOD, HEIGHT, NEXT_STEP, START };

const int model_number_of_variables = 6;
const int model_number_of_states = 0;
const int model_number_of_indicators = 0;
const double model_max_substep = 1e-3;

void model_defaults(Model* m) {
  m->value[PERIOD] = 0.01;
  m->value[HEIGHT] = 0.001;
  m->value[COUNT] = 0;
}
void model_initialize(Model* m) {
  m->value[COUNT] = 0;
  m->value[START] = m->time;
  m->value[NEXT_STEP] = m->time + m->value[PERIOD];
}
void model_derivatives(const Model* m, double* dxdt) {}
void model_outputs(Model* m) { m->value[Y] = m->value[HEIGHT] * m->value[COUNT]; }
void model_event_indicators(const Model* m, double* z) {}
double model_next_event_time(const Model* m) { return m->value[NEXT_STEP]; }
int model_event(Model* m) {
  /* Due at or after its time (a few ulps early counts, as the importer's bisection lands
   * within its resolution); the next step is computed from the count, never accumulated. */
  if (m->time < m->value[NEXT_STEP] - 1e-9 * m->value[PERIOD]) return 0;
  m->value[COUNT] += 1;
  m->value[NEXT_STEP] = m->value[START] + (m->value[COUNT] + 1) * m->value[PERIOD];
  return 0;
}
int model_check(Model* m, double t_end) {
  if (m->value[PERIOD] > 0) return 0;
  m->error = "staircase: period must be > 0";
  return 1;
}
