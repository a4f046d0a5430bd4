// Test helper: integrate a Block with the classical fixed-step RK4, calling its sampled
// update at t0 + j T (T must be a whole number of steps). The inputs are held at the given
// constant vector. Records every output at every `record_every`-th step.
#pragma once

#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "mechsim/models/block.h"

namespace mechsim::models::nc::testing {

struct Trajectory {
  std::vector<double> time;
  std::vector<std::vector<double>> outputs;  // outputs[k][port]
  std::vector<double> final_state;

  std::vector<double> signal(int port) const {
    std::vector<double> s;
    for (const auto& y : outputs) s.push_back(y[port]);
    return s;
  }
};

inline Trajectory integrate_rk4(Block& block, double t_end, double step, std::vector<double> inputs = {},
                                int record_every = 1) {
  if (inputs.empty()) inputs = block.default_inputs();
  const int n = block.num_states();
  const long steps = std::lround(t_end / step);
  long steps_per_sample = 0;
  if (block.sample_time() > 0) {
    steps_per_sample = std::lround(block.sample_time() / step);
    if (steps_per_sample < 1 || std::abs(steps_per_sample * step - block.sample_time()) > 1e-9 * step)
      throw std::invalid_argument("integrate_rk4: the sample time must be a multiple of the step");
  }
  std::vector<double> x(n), k1(n), k2(n), k3(n), k4(n), tmp(n), y(block.num_outputs());
  block.initial_state(0.0, x);
  Trajectory out;
  auto record = [&](double t) {
    block.calc_outputs(t, x, inputs, y);
    out.time.push_back(t);
    out.outputs.push_back(y);
  };
  for (long k = 0; k < steps; ++k) {
    const double t = k * step;  // computed, never accumulated
    if (steps_per_sample > 0 && k % steps_per_sample == 0) block.discrete_update(t, x, inputs);
    if (k % record_every == 0) record(t);
    block.derivatives(t, x, inputs, k1);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * step * k1[i];
    block.derivatives(t + 0.5 * step, tmp, inputs, k2);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * step * k2[i];
    block.derivatives(t + 0.5 * step, tmp, inputs, k3);
    for (int i = 0; i < n; ++i) tmp[i] = x[i] + step * k3[i];
    block.derivatives(t + step, tmp, inputs, k4);
    for (int i = 0; i < n; ++i) x[i] += step / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  const double t_final = steps * step;
  if (steps_per_sample > 0 && steps % steps_per_sample == 0) block.discrete_update(t_final, x, inputs);
  record(t_final);
  out.final_state = x;
  return out;
}

// Step-response figures of a signal that moves from 0 to `target`.
struct StepMetrics {
  double rise_time;      // 10 % -> 90 % of target [s]
  double settling_time;  // last exit from the ±2 % band around target [s]
  double overshoot;      // max(signal)/target − 1 (negative: never reaches target)
};

inline double crossing_time(const std::vector<double>& t, const std::vector<double>& s, double level) {
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i - 1] < level && s[i] >= level) return t[i - 1] + (level - s[i - 1]) / (s[i] - s[i - 1]) * (t[i] - t[i - 1]);
  return NAN;
}

inline StepMetrics step_metrics(const std::vector<double>& t, const std::vector<double>& s, double target) {
  StepMetrics m{};
  m.rise_time = crossing_time(t, s, 0.9 * target) - crossing_time(t, s, 0.1 * target);
  double peak = s[0];
  for (double v : s) peak = std::max(peak, v);
  m.overshoot = peak / target - 1;
  m.settling_time = 0;
  const double band = 0.02 * std::abs(target);
  for (std::size_t i = s.size() - 1; i > 0; --i)
    if (std::abs(s[i - 1] - target) > band) {
      // Interpolate the exit from the band between samples i−1 and i.
      const double level = s[i - 1] < target ? target - band : target + band;
      m.settling_time = t[i - 1] + (level - s[i - 1]) / (s[i] - s[i - 1]) * (t[i] - t[i - 1]);
      break;
    }
  return m;
}

}  // namespace mechsim::models::nc::testing
