/* An integrator dy/dt = u that misbehaves on request, for the importer's error tests.
 * Parameter `fault` (Integer): 0 none; 1 the step (co-simulation) or the derivatives (model
 * exchange) fail with an error status once t passes fault_time; 2 the output y is NaN from
 * fault_time on; 3 the process aborts once t passes fault_time (a crashing FMU); 4 the
 * process exits with code 0 once t passes fault_time (a run that ends early, looking clean);
 * 5 it writes through a null pointer once t passes fault_time (a segmentation fault).
 * Value references: 0 u [V] input, 1 y [V s] output (the state), 2 der(y) [V], 3 fault,
 * 4 fault_time [s] parameters, 5 faulted (Boolean output: t >= fault_time). */
#include <math.h>
#include <stdlib.h>

#include "model.h"

enum { U, Y, DER_Y, FAULT, FAULT_TIME, FAULTED };

const int model_number_of_variables = 6;
const int model_number_of_states = 1;
const int model_number_of_indicators = 0;
const double model_max_substep = 1e-3;

void model_defaults(Model* m) {
  m->value[U] = 0.0;
  m->value[FAULT] = 0;
  m->value[FAULT_TIME] = 0.0;
}
void model_initialize(Model* m) { m->x[0] = 0.0; }
void model_derivatives(const Model* m, double* dxdt) { dxdt[0] = m->value[U]; }
void model_outputs(Model* m) {
  const int faulted = m->time >= m->value[FAULT_TIME];
  m->value[Y] = (m->value[FAULT] == 2 && faulted) ? NAN : m->x[0];
  m->value[DER_Y] = m->value[U];
  m->value[FAULTED] = faulted;
}
void model_event_indicators(const Model* m, double* z) {}
int model_event(Model* m) { return 0; }
int model_check(Model* m, double t_end) {
  if (t_end <= m->value[FAULT_TIME]) return 0;
  if (m->value[FAULT] == 3) abort();
  if (m->value[FAULT] == 4) exit(0);
  if (m->value[FAULT] == 5) {
    volatile int* nowhere = NULL;
    *nowhere = 1;
  }
  if (m->value[FAULT] != 1) return 0;
  m->error = "injected fault: the step fails past fault_time";
  return 1;
}
