/* A model with time events and a discrete state: a counter n that steps up by one at every
 * t_k = t0 + k * period (k >= 1), scheduled as the FMU's next time event (nextEventTime),
 * and y integrating it, dy/dt = n, y(t0) = 0. With t0 = 0 and n = floor(t / period):
 *   y(t) = period n (n - 1) / 2 + n (t - n period).
 * The counter is the FMU's own discrete state (not a continuous state): a checkpoint that
 * held only the continuous states would lose it. Value references: 0 y [s] output (the
 * state), 1 count (Integer output), 2 period [s] parameter, 3 next_tick [s] local,
 * 4 der(y) [1]; 5 the start time (internal, not in the description). No inputs. */
#include <math.h>

#include "model.h"

enum { Y, COUNT, PERIOD, NEXT_TICK, DER_Y, START };

const int model_number_of_variables = 6;
const int model_number_of_states = 1;
const int model_number_of_indicators = 0;
const double model_max_substep = 1e-4;

void model_defaults(Model* m) {
  m->value[PERIOD] = 0.01;
  m->value[COUNT] = 0;
}
void model_initialize(Model* m) {
  m->x[0] = 0.0;
  m->value[COUNT] = 0;
  m->value[START] = m->time;
  m->value[NEXT_TICK] = m->time + m->value[PERIOD];
}
void model_derivatives(const Model* m, double* dxdt) { dxdt[0] = m->value[COUNT]; }
void model_outputs(Model* m) {
  m->value[Y] = m->x[0];
  m->value[DER_Y] = m->value[COUNT];
}
void model_event_indicators(const Model* m, double* z) {}
double model_next_event_time(const Model* m) { return m->value[NEXT_TICK]; }
int model_event(Model* m) {
  /* A tick is due at or after its time (a few ulps early counts: the importer's root
   * finding lands on it to its resolution). The next tick is computed from the count,
   * never accumulated. */
  if (m->time < m->value[NEXT_TICK] - 1e-9 * m->value[PERIOD]) return 0;
  m->value[COUNT] += 1;
  m->value[NEXT_TICK] = m->value[START] + (m->value[COUNT] + 1) * m->value[PERIOD];
  return 0;
}
int model_check(Model* m, double t_end) {
  if (m->value[PERIOD] > 0) return 0;
  m->error = "ticker: period must be > 0";
  return 1;
}
