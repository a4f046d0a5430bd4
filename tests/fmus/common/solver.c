/* The co-simulation FMUs' own integrator: classic RK4 with fixed substeps, inputs held over
 * the step (as the importer sets them before the step). A falling (> 0 to <= 0) event
 * indicator within a substep is located by bisection to 1e-13 s, the model handles the
 * event there and integration resumes. A substep ends on a time event, which the model
 * handles there. */
#include <math.h>
#include <string.h>

#include "model.h"

static void rk4(Model* m, double h) {
  const int n = model_number_of_states;
  double x0[MODEL_MAX_STATES], k1[MODEL_MAX_STATES], k2[MODEL_MAX_STATES], k3[MODEL_MAX_STATES],
      k4[MODEL_MAX_STATES];
  const double t0 = m->time;
  memcpy(x0, m->x, sizeof x0);
  model_derivatives(m, k1);
  for (int i = 0; i < n; ++i) m->x[i] = x0[i] + 0.5 * h * k1[i];
  m->time = t0 + 0.5 * h;
  model_derivatives(m, k2);
  for (int i = 0; i < n; ++i) m->x[i] = x0[i] + 0.5 * h * k2[i];
  model_derivatives(m, k3);
  for (int i = 0; i < n; ++i) m->x[i] = x0[i] + h * k3[i];
  m->time = t0 + h;
  model_derivatives(m, k4);
  for (int i = 0; i < n; ++i) m->x[i] = x0[i] + h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

static int crossed(const double* before, const double* after) {
  for (int i = 0; i < model_number_of_indicators; ++i)
    if (before[i] > 0 && after[i] <= 0) return 1;
  return 0;
}

double next_time_event(const Model* m) { return model_next_event_time ? model_next_event_time(m) : INFINITY; }

int model_advance(Model* m, double t_end) {
  while (m->time < t_end) {
    const double te = next_time_event(m);
    if (te <= m->time) {  /* due (e.g. scheduled at the step's start) */
      model_event(m);
      continue;
    }
    double h = fmin(model_max_substep, t_end - m->time);
    const int timed = te <= m->time + h;
    if (timed) h = te - m->time;
    Model start = *m;
    double z0[MODEL_MAX_INDICATORS], z1[MODEL_MAX_INDICATORS];
    model_event_indicators(m, z0);
    rk4(m, h);
    model_event_indicators(m, z1);
    if (!crossed(z0, z1)) {
      if (timed) {
        m->time = te;
        model_event(m);
      }
      continue;
    }
    /* Bisection on the substep length: lo without the crossing, hi with it. */
    double lo = 0.0, hi = h;
    while (hi - lo > 1e-13) {
      const double mid = 0.5 * (lo + hi);
      *m = start;
      rk4(m, mid);
      model_event_indicators(m, z1);
      if (crossed(z0, z1)) hi = mid; else lo = mid;
    }
    *m = start;
    rk4(m, hi);
    model_event(m);
  }
  m->time = t_end;
  return 0;
}
