// Test helper: a follower block driven by a constant-speed cam shaft, integrated by the
// same BlockIntegrator the nodes use. The cam has no state at constant speed, so its
// outputs at t are the follower's exact inputs: no coupling error enters these tests.
#pragma once

#include <functional>
#include <span>
#include <stdexcept>
#include <vector>

#include "mechsim/models/cam/cam_shaft_block.h"
#include "mechsim/models/cam/press_cam.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::testing {

// The press cam at a constant speed (rad/s), e = 0, starting at θ = 0.
inline models::cam::CamShaftBlock press_cam_shaft(double speed_rad_s) {
  const models::cam::PressCam c;
  return models::cam::CamShaftBlock({c.law(), c.pitch_radius_m, c.eccentricity_m, speed_rad_s, 0.0});
}

struct DrivenRun {
  solve::SolverStats stats;
  std::vector<models::BlockEvent> events;
};

// Integrates `follower` over [0, t_end], fed from `cam` (inputs by name: angle, speed,
// lift, ...). `sample_times` (ascending) are stopped at exactly; `on_sample(t, x, u)` sees
// the follower's state and inputs there. options.max_step must be set: a follower at rest
// in a dwell has zero derivatives, and an unbounded solver would step over the whole cam
// motion in one go (a node is bounded by its macro step instead).
inline DrivenRun drive_follower(
    models::Block& follower, const models::cam::CamShaftBlock& cam, double t_end, solve::SolverOptions options,
    const std::vector<double>& sample_times = {},
    const std::function<void(double, std::span<const double>, std::span<const double>)>& on_sample = {}) {
  std::vector<int> source(follower.num_inputs());
  for (int i = 0; i < follower.num_inputs(); ++i) source[i] = cam.output_index(follower.inputs()[i].name);
  std::vector<double> y_cam(cam.num_outputs());
  const std::vector<double> defaults = follower.default_inputs();
  const solve::InputFunction inputs = [&](double t, std::span<double> u) {
    cam.calc_outputs(t, {}, std::vector<double>(cam.num_inputs(), 0.0), y_cam);
    for (int i = 0; i < follower.num_inputs(); ++i) u[i] = source[i] >= 0 ? y_cam[source[i]] : defaults[i];
  };
  if (!(options.max_step > 0.0)) throw std::invalid_argument("drive_follower: set options.max_step");
  std::vector<double> x(follower.num_states());
  follower.initial_state(0.0, x);
  solve::BlockIntegrator integrator(follower, options, 0.0, x);
  DrivenRun run;
  std::vector<double> u(follower.num_inputs());
  for (double t : sample_times) {
    if (t > t_end) break;
    integrator.advance_to(t, inputs);
    inputs(t, u);
    if (on_sample) on_sample(t, integrator.state(), u);
  }
  integrator.advance_to(t_end, inputs);
  run.stats = integrator.stats();
  run.events = follower.take_event_log();
  return run;
}

}  // namespace mechsim::testing
