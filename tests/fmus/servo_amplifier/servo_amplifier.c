/* The NC slide's servo amplifier (spec nc_slide.md §3; the native block is
 * libs/models/.../nc/servo_amplifier_block.h) as an FMU, continuous, without the current
 * limit and the velocity feed-forward:
 *   φ_ref = 2π x_ref / lead,   x_ref = position_setpoint + step_distance
 *   e     = α (K_v (φ_ref − φ_a)) − U_Tf
 *   u     = K_sv e + z,   U_a = clamp(u, −U_max, U_max)
 *   dz/dt = (K_sv/T_i) e + (U_a − u)/T_t,   τ_f dU_Tf/dt = U_T − U_Tf
 * step_distance is a setpoint step at the start (the shipped scene's step of 0.1 mm at 0 s).
 * Value references: see the enum; states z (integrator) and U_Tf (filtered_tacho_voltage). */
#include <math.h>

#include "model.h"

enum {
  TACHO_VOLTAGE, SPINDLE_ANGLE, POSITION_SETPOINT,                         /* inputs */
  ARMATURE_VOLTAGE, POSITION_REFERENCE, FOLLOWING_ERROR, VELOCITY_ERROR, SATURATED, /* outputs */
  POSITION_GAIN, VELOCITY_GAIN, INTEGRAL_TIME, ANTIWINDUP_TIME, TACHO_FILTER_TIME, VOLTAGE_LIMIT,
  TACHO_CONSTANT, LEAD, STEP_DISTANCE,                                     /* parameters */
  INTEGRATOR, FILTERED_TACHO_VOLTAGE, DER_INTEGRATOR, DER_FILTERED_TACHO_VOLTAGE /* states */
};

const int model_number_of_variables = 21;
const int model_number_of_states = 2;
const int model_number_of_indicators = 0;
const double model_max_substep = 1e-6; /* well below τ_f = 0.3 ms: RK4 accurate to round-off */

static const double two_pi = 6.283185307179586476925286766559;

void model_defaults(Model* m) {
  m->value[POSITION_GAIN] = 40.0;
  m->value[VELOCITY_GAIN] = 10.0;
  m->value[INTEGRAL_TIME] = 0.01;
  m->value[ANTIWINDUP_TIME] = 5e-3;
  m->value[TACHO_FILTER_TIME] = 0.3e-3;
  m->value[VOLTAGE_LIMIT] = 50.0;
  m->value[TACHO_CONSTANT] = 0.0496;
  m->value[LEAD] = 0.005;
  m->value[STEP_DISTANCE] = 0.0;
}
void model_initialize(Model* m) {
  m->x[0] = 0.0;
  m->x[1] = 0.0;
}

typedef struct {
  double reference, velocity_error, unclamped, voltage, integrator_rate;
} Law;

static Law evaluate(const Model* m) {
  const double* p = m->value;
  Law law;
  law.reference = p[POSITION_SETPOINT] + p[STEP_DISTANCE];
  const double position_error = two_pi / p[LEAD] * law.reference - p[SPINDLE_ANGLE];
  law.velocity_error = p[TACHO_CONSTANT] * (p[POSITION_GAIN] * position_error) - m->x[1];
  law.unclamped = p[VELOCITY_GAIN] * law.velocity_error + m->x[0];
  law.voltage = fmin(fmax(law.unclamped, -p[VOLTAGE_LIMIT]), p[VOLTAGE_LIMIT]);
  law.integrator_rate = p[VELOCITY_GAIN] / p[INTEGRAL_TIME] * law.velocity_error +
                        (law.voltage - law.unclamped) / p[ANTIWINDUP_TIME];
  return law;
}

void model_derivatives(const Model* m, double* dxdt) {
  dxdt[0] = evaluate(m).integrator_rate;
  dxdt[1] = (m->value[TACHO_VOLTAGE] - m->x[1]) / m->value[TACHO_FILTER_TIME];
}
void model_outputs(Model* m) {
  const Law law = evaluate(m);
  double d[2];
  model_derivatives(m, d);
  m->value[ARMATURE_VOLTAGE] = law.voltage;
  m->value[POSITION_REFERENCE] = law.reference;
  m->value[FOLLOWING_ERROR] = law.reference - m->value[SPINDLE_ANGLE] * m->value[LEAD] / two_pi;
  m->value[VELOCITY_ERROR] = law.velocity_error;
  m->value[SATURATED] = law.voltage != law.unclamped;
  m->value[INTEGRATOR] = m->x[0];
  m->value[FILTERED_TACHO_VOLTAGE] = m->x[1];
  m->value[DER_INTEGRATOR] = d[0];
  m->value[DER_FILTERED_TACHO_VOLTAGE] = d[1];
}
void model_event_indicators(const Model* m, double* z) {}
int model_event(Model* m) { return 0; }
int model_check(Model* m, double t_end) {
  const double* p = m->value;
  if (p[POSITION_GAIN] > 0 && p[VELOCITY_GAIN] > 0 && p[INTEGRAL_TIME] > 0 && p[ANTIWINDUP_TIME] > 0 &&
      p[TACHO_FILTER_TIME] > 0 && p[VOLTAGE_LIMIT] > 0 && p[TACHO_CONSTANT] > 0 && p[LEAD] > 0)
    return 0;
  m->error = "servo_amplifier: gains, times, voltage limit, tacho constant and lead must be > 0";
  return 1;
}
