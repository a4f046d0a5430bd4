/* First-order lag  T dy/dt = k u - y,  y(0) = y0: the parameterised linear system whose
 * closed form the importer tests compare with. For u constant over [t0, t],
 *   y(t) = k u + (y(t0) - k u) exp(-(t - t0) / T).
 * Value references: 0 u [V] input, 1 y [V] output (the state), 2 der(y) [V/s],
 * 3 k [1], 4 T [s], 5 y0 [V] parameters. */
#include <math.h>

#include "model.h"

enum { U, Y, DER_Y, K, T, Y0 };

const int model_number_of_variables = 6;
const int model_number_of_states = 1;
const int model_number_of_indicators = 0;
const double model_max_substep = 1e-4;

void model_defaults(Model* m) {
  m->value[U] = 0.0;
  m->value[K] = 1.0;
  m->value[T] = 0.1;
  m->value[Y0] = 0.0;
}
void model_initialize(Model* m) { m->x[0] = m->value[Y0]; }
void model_derivatives(const Model* m, double* dxdt) {
  dxdt[0] = (m->value[K] * m->value[U] - m->x[0]) / m->value[T];
}
void model_outputs(Model* m) {
  double d;
  model_derivatives(m, &d);
  m->value[Y] = m->x[0];
  m->value[DER_Y] = d;
}
void model_event_indicators(const Model* m, double* z) {}
int model_event(Model* m) { return 0; }
int model_check(Model* m, double t_end) {
  if (m->value[T] > 0) return 0;
  m->error = "the time constant T must be > 0";
  return 1;
}
