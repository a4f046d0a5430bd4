/* A mass bouncing on a cam-like contact: a model with state events. The contact surface
 * moves as s(t) = lift/2 (1 − cos ω t); the mass flies freely (dh/dt = v, dv/dt = −g)
 * while its gap z = h − s(t) is positive. When z falls through 0 the event handler
 * reflects the velocity relative to the surface with restitution e:
 *   v+ = s'(t) − e (v − s'(t)).
 * With lift = 0 (a fixed floor) the bounces have a closed form: first impact at
 * t1 = sqrt(2 h0 / g), the k-th flight lasts 2 e^k t1, the k-th apex is e^(2k) h0.
 * Value references: see the enum; impacts (Integer output) counts the events. */
#include <math.h>

#include "model.h"

enum {
  HEIGHT, VELOCITY, GAP, IMPACTS,                       /* outputs */
  GRAVITY, RESTITUTION, LIFT, CAM_SPEED, H0, V0,        /* parameters */
  DER_HEIGHT, DER_VELOCITY                              /* derivatives */
};

const int model_number_of_variables = 12;
const int model_number_of_states = 2;
const int model_number_of_indicators = 1;
const double model_max_substep = 1e-4;

static double surface(const Model* m) {
  return 0.5 * m->value[LIFT] * (1.0 - cos(m->value[CAM_SPEED] * m->time));
}
static double surface_speed(const Model* m) {
  return 0.5 * m->value[LIFT] * m->value[CAM_SPEED] * sin(m->value[CAM_SPEED] * m->time);
}

void model_defaults(Model* m) {
  m->value[GRAVITY] = 9.81;
  m->value[RESTITUTION] = 0.8;
  m->value[LIFT] = 0.0;
  m->value[CAM_SPEED] = 0.0;
  m->value[H0] = 1.0;
  m->value[V0] = 0.0;
  m->value[IMPACTS] = 0;
}
void model_initialize(Model* m) {
  m->x[0] = m->value[H0];
  m->x[1] = m->value[V0];
  m->value[IMPACTS] = 0;
}
void model_derivatives(const Model* m, double* dxdt) {
  dxdt[0] = m->x[1];
  dxdt[1] = -m->value[GRAVITY];
}
void model_outputs(Model* m) {
  m->value[HEIGHT] = m->x[0];
  m->value[VELOCITY] = m->x[1];
  m->value[GAP] = m->x[0] - surface(m);
  m->value[DER_HEIGHT] = m->x[1];
  m->value[DER_VELOCITY] = -m->value[GRAVITY];
}
void model_event_indicators(const Model* m, double* z) { z[0] = m->x[0] - surface(m); }
int model_event(Model* m) {
  /* Only an approach (relative velocity downwards) at contact is an impact; the event
   * iteration after initialization and a grazing contact leave the state alone. */
  const double ds = surface_speed(m);
  if (m->x[0] - surface(m) > 1e-12 || m->x[1] - ds >= 0) return 0;
  m->x[1] = ds - m->value[RESTITUTION] * (m->x[1] - ds);
  m->value[IMPACTS] += 1;
  return 1;
}
int model_check(Model* m, double t_end) { return 0; }
