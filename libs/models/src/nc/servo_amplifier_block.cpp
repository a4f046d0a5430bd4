#include "mechsim/models/nc/servo_amplifier_block.h"

#include <algorithm>
#include <numbers>
#include <stdexcept>

namespace mechsim::models::nc {

ServoAmplifierBlock::ServoAmplifierBlock(ServoAmplifierParams params)
    : Block("servo_amplifier"), params_(std::move(params)) {
  const auto& p = params_;
  if (!(p.position_gain > 0 && p.velocity_gain > 0 && p.integral_time > 0 && p.antiwindup_time > 0 &&
        p.tacho_filter_time > 0 && p.voltage_limit > 0 && p.tacho_constant > 0 && p.lead > 0))
    throw std::invalid_argument("servo_amplifier: gains, times, voltage limit, α and lead must be > 0");
  if (p.sample_time < 0) throw std::invalid_argument("servo_amplifier: sample_time must be >= 0");
  if (p.current_limit.enabled && !(p.current_limit.max_current > 0 && p.current_limit.armature_resistance > 0))
    throw std::invalid_argument("servo_amplifier: current limit needs I_max > 0 and R_a > 0");
  if (p.setpoint_source == SetpointSource::internal) p.setpoint.validate();

  in_.tacho_voltage = declare_required_input("tacho_voltage", "V");
  in_.spindle_angle = declare_required_input(p.measure_on_motor ? "motor_angle" : "spindle_angle", "rad");
  if (p.setpoint_source == SetpointSource::external)
    in_.position_setpoint = declare_required_input("position_setpoint", "m");

  std::vector<int> reference_ft, error_ft, voltage_ft;
  if (!sampled()) {
    if (in_.position_setpoint >= 0) reference_ft.push_back(in_.position_setpoint);
    error_ft = reference_ft;
    error_ft.push_back(in_.spindle_angle);
    voltage_ft = error_ft;
    if (p.current_limit.enabled) voltage_ft.push_back(in_.tacho_voltage);
  }
  out_.armature_voltage = declare_output("armature_voltage", "V", voltage_ft);
  out_.position_reference = declare_output("position_reference", "m", reference_ft);
  // Setpoint minus the measured position (the indirect measurement through the spindle).
  out_.following_error = declare_output("following_error", "m", error_ft);
  out_.velocity_error = declare_output("velocity_error", "V", error_ft);
  out_.saturated = declare_output("saturated", "1", voltage_ft);

  st_.integrator = declare_state("integrator", "V");
  st_.filtered_tacho_voltage = declare_state("filtered_tacho_voltage", "V");
}

ServoAmplifierBlock::Measured ServoAmplifierBlock::measure(double t, std::span<const double> u) const {
  Measured m;
  m.tacho_voltage = u[in_.tacho_voltage];
  m.spindle_angle = u[in_.spindle_angle];
  if (params_.setpoint_source == SetpointSource::external) {
    m.reference = u[in_.position_setpoint];
  } else {
    m.reference = params_.setpoint.position(t);
    m.reference_velocity = params_.setpoint.velocity_at(t);
  }
  return m;
}

ServoAmplifierBlock::Law ServoAmplifierBlock::evaluate(const Measured& m, double integrator,
                                                       double filtered_tacho) const {
  const auto& p = params_;
  const double radians_per_metre = 2 * std::numbers::pi / p.lead;
  Law law{};
  const double position_error = radians_per_metre * m.reference - m.spindle_angle;
  law.velocity_error = p.tacho_constant * (p.position_gain * position_error +
                                           p.velocity_feedforward * radians_per_metre * m.reference_velocity) -
                       filtered_tacho;
  law.unclamped = p.velocity_gain * law.velocity_error + integrator;

  double lo = -p.voltage_limit, hi = p.voltage_limit;
  if (p.current_limit.enabled) {
    const auto& cl = p.current_limit;
    const double back_emf = cl.back_emf_per_tacho_volt * m.tacho_voltage;
    const double headroom = cl.armature_resistance * cl.max_current;
    lo = std::max(lo, back_emf - headroom);
    hi = std::min(hi, back_emf + headroom);
  }
  law.voltage = std::min(std::max(law.unclamped, lo), hi);
  law.saturated = law.voltage != law.unclamped;
  law.integrator_rate =
      p.velocity_gain / p.integral_time * law.velocity_error + (law.voltage - law.unclamped) / p.antiwindup_time;
  return law;
}

void ServoAmplifierBlock::derivatives(double t, std::span<const double> x, std::span<const double> u,
                                      std::span<double> dxdt) const {
  const Measured m = sampled() ? held_.sample : measure(t, u);
  const double filtered = x[st_.filtered_tacho_voltage];
  dxdt[st_.filtered_tacho_voltage] = (m.tacho_voltage - filtered) / params_.tacho_filter_time;
  dxdt[st_.integrator] = evaluate(m, x[st_.integrator], filtered).integrator_rate;
}

void ServoAmplifierBlock::calc_outputs(double t, std::span<const double> x, std::span<const double> u,
                                       std::span<double> y) const {
  if (sampled()) {
    y[out_.armature_voltage] = held_.voltage;
    y[out_.position_reference] = held_.sample.reference;
    y[out_.following_error] = held_.sample.reference - held_.sample.spindle_angle * params_.lead / (2 * std::numbers::pi);
    y[out_.velocity_error] = held_.velocity_error;
    y[out_.saturated] = held_.saturated;
    return;
  }
  const Measured m = measure(t, u);
  const Law law = evaluate(m, x[st_.integrator], x[st_.filtered_tacho_voltage]);
  y[out_.armature_voltage] = law.voltage;
  y[out_.position_reference] = m.reference;
  y[out_.following_error] = m.reference - m.spindle_angle * params_.lead / (2 * std::numbers::pi);
  y[out_.velocity_error] = law.velocity_error;
  y[out_.saturated] = law.saturated ? 1.0 : 0.0;
}

void ServoAmplifierBlock::discrete_update(double t, std::span<double> x, std::span<const double> u) {
  if (!sampled()) return;
  held_.sample = measure(t, u);
  const Law law = evaluate(held_.sample, x[st_.integrator], x[st_.filtered_tacho_voltage]);
  held_.voltage = law.voltage;
  held_.velocity_error = law.velocity_error;
  held_.saturated = law.saturated ? 1.0 : 0.0;
}

std::vector<double> ServoAmplifierBlock::save_discrete_state() const {
  if (!sampled()) return {};
  const Measured& m = held_.sample;
  return {m.tacho_voltage, m.spindle_angle,   m.reference, m.reference_velocity,
          held_.voltage,   held_.velocity_error, held_.saturated};
}

void ServoAmplifierBlock::restore_discrete_state(std::span<const double> saved) {
  if (!sampled()) return;
  if (saved.size() != held_size) throw std::invalid_argument("servo_amplifier: discrete state needs 7 values");
  held_ = {{saved[0], saved[1], saved[2], saved[3]}, saved[4], saved[5], saved[6]};
}

std::vector<double> ServoAmplifierBlock::scheduled_events(double t0, double t_end) const {
  std::vector<double> inside;
  if (params_.setpoint_source != SetpointSource::internal) return inside;
  for (double t : params_.setpoint.corners())
    if (t > t0 && t < t_end) inside.push_back(t);
  return inside;
}

}  // namespace mechsim::models::nc
