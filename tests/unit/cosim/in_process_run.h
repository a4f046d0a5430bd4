// Test helper: a whole scene run in one process with the product's NodeSteppers, samples
// and coupling predictions handed over in memory (no transport). Same protocol, same
// numbers as a DDS run (results do not depend on timing, docs/protocol.md), fast enough for
// unit tests and sweeps of the macro step.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/divergence_guard.h"
#include "mechsim/cosim/node_stepper.h"

namespace mechsim::testing {

struct InProcessRun {
  std::vector<std::vector<std::vector<double>>> outputs;  // [node][step][block output]
  std::optional<std::string> diverged;                     // the divergence guard's reason
  // Column of "participant.output" over the steps (NaN-free only when not diverged).
  std::vector<double> signal(const cosim::ScenePlan& plan, const std::string& participant, const std::string& output) const {
    std::size_t i = 0;
    while (plan.nodes()[i].name() != participant) ++i;
    const int o = plan.nodes()[i].block->output_index(output);
    if (o < 0) throw std::invalid_argument("no output " + output);
    std::vector<double> s;
    for (const auto& y : outputs[i]) s.push_back(y[o]);
    return s;
  }
};

inline InProcessRun run_in_process(cosim::ScenePlan& plan) {
  auto& nodes = plan.nodes();
  const std::size_t n = nodes.size();
  std::vector<std::unique_ptr<cosim::NodeStepper>> steppers;
  std::vector<std::unique_ptr<cosim::DivergenceGuard>> guards;
  for (auto& node : nodes) {
    steppers.push_back(std::make_unique<cosim::NodeStepper>(node, plan.scene().time));
    std::vector<std::string> names;
    for (const auto& o : node.block->outputs()) names.push_back(o.name);
    guards.push_back(std::make_unique<cosim::DivergenceGuard>(names));
  }
  auto index_of = [&](const std::string& name) {
    for (std::size_t i = 0; i < n; ++i)
      if (nodes[i].name() == name) return i;
    throw std::logic_error("no participant " + name);
  };
  InProcessRun run;
  run.outputs.resize(n);
  std::vector<bool> initialised(n, false);
  std::vector<double> values, prediction;
  auto publish = [&](std::size_t i) {
    const std::uint64_t k = steppers[i]->step();
    run.outputs[i].push_back(steppers[i]->outputs());
    if (auto why = guards[i]->check(steppers[i]->outputs())) run.diverged = nodes[i].name() + ": " + *why;
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t e = 0; e < nodes[j].inputs.size(); ++e)
        if (nodes[j].inputs[e].from == nodes[i].name()) steppers[j]->channel(e).add(k, values);
  };
  for (;;) {
    bool progressed = false, all_done = true;
    for (std::size_t i = 0; i < n && !run.diverged; ++i) {
      cosim::NodeStepper& s = *steppers[i];
      if (!initialised[i] && s.can_initialise()) {
        s.initialise(values);
        initialised[i] = true;
        publish(i);
        progressed = true;
      }
      if (s.prediction_due()) {
        s.predict(prediction);
        steppers[index_of(nodes[i].cut->partner)]->add_partner_prediction(s.step(), prediction);
        progressed = true;
      }
      if (s.can_step()) {
        s.step(values);
        publish(i);
        progressed = true;
      }
      all_done = all_done && s.finished();
    }
    if (run.diverged || all_done) return run;
    if (!progressed) throw std::logic_error("in-process run: deadlock");
  }
}

// 10-90 % rise time of a step response towards `target`, with linear interpolation between
// samples t_k = k h; NaN when it never gets there.
inline double rise_time(const std::vector<double>& x, double h, double target) {
  auto crossing = [&](double level) {
    for (std::size_t k = 1; k < x.size(); ++k)
      if (x[k] >= level && x[k - 1] < level) return h * (static_cast<double>(k - 1) + (level - x[k - 1]) / (x[k] - x[k - 1]));
    return std::nan("");
  };
  return crossing(0.9 * target) - crossing(0.1 * target);
}

}  // namespace mechsim::testing
