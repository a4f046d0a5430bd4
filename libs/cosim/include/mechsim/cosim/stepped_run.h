// One in-process run of a scene stepped by hand with the product's NodeSteppers (the code
// of every node process, without transport: the numbers of a DDS run, docs/protocol.md):
// samples and coupling predictions handed over in memory, a step barrier (advance) for the
// linear analysis of the macro-step map. Used by `mechsim bench --stability` and the
// launcher's stable-step search (libs/assess stable_step.h) and by unit tests that sweep
// the macro step. For a run with the node threads and the in-process transport, see
// inproc_run.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/divergence_guard.h"
#include "mechsim/cosim/node_stepper.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::cosim {

// One in-process run of a scene, stepped by hand: the NodeSteppers of every node, samples
// and predictions handed over in memory, a step barrier for the linear analysis.
class SteppedRun {
 public:
  SteppedRun(const std::string& path, const std::vector<std::string>& overrides)
      : scene_(std::make_unique<config::Scene>(config::load_scene(path, overrides))),
        plan_(std::make_unique<ScenePlan>(ScenePlan::build(*scene_))) {
    for (auto& node : plan_->nodes()) {
      steppers_.push_back(std::make_unique<NodeStepper>(node, plan_->grid(), plan_->nodes().size(), steppers_.size()));
      std::vector<std::string> names;
      for (const auto& o : node.block->outputs()) names.push_back(o.name);
      guards_.push_back(std::make_unique<DivergenceGuard>(names));
      torque_output_.push_back(node.block->output_index("coupling_torque"));
    }
    initialised_.assign(steppers_.size(), false);
    // Who reads whose samples, looked up once: a publish then costs no name comparisons.
    auto& nodes = plan_->nodes();
    readers_.resize(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (std::size_t j = 0; j < nodes.size(); ++j)
        for (std::size_t e = 0; e < nodes[j].inputs.size(); ++e)
          if (nodes[j].inputs[e].from == nodes[i].name()) readers_[i].push_back({j, e});
  }

  const config::Scene& scene() const { return *scene_; }
  const ScenePlan& plan() const { return *plan_; }
  // Called with (node index, step, the node's outputs) each time a node publishes a step.
  std::function<void(std::size_t, std::uint64_t, const std::vector<double>&)> on_publish;
  // Steps of the run (adaptive: the steps agreed so far; advance(kToTheEnd) runs to the end).
  std::uint64_t steps() const { return plan_->grid()->steps(); }
  static constexpr std::uint64_t kToTheEnd = UINT64_MAX;
  const std::optional<std::string>& diverged() const { return diverged_; }
  // Spring energy T^2/(2C) per step (max over the nodes that publish coupling_torque).
  const std::vector<double>& energy() const { return energy_; }
  // Tracks the spring energy of a coupling element of stiffness C between participants a
  // and b (from their coupling_torque outputs); C <= 0: none.
  void watch_energy(const std::string& a, const std::string& b, double stiffness) {
    if (stiffness <= 0) return;
    stiffness_ = stiffness;
    for (std::size_t i = 0; i < steppers_.size(); ++i) {
      const std::string& n = plan_->nodes()[i].name();
      energy_nodes_.push_back(i < torque_output_.size() && (n == a || n == b) && torque_output_[i] >= 0);
    }
  }

  // Steps every node up to step `target` (each stops there), or until a guard fires.
  void advance(std::uint64_t target) {
    auto& nodes = plan_->nodes();
    const std::size_t n = nodes.size();
    for (;;) {
      bool progressed = false, all_there = true;
      for (std::size_t i = 0; i < n && !diverged_; ++i) {
        NodeStepper& s = *steppers_[i];
        if (!initialised_[i] && s.can_initialise()) {
          s.initialise(values_);
          initialised_[i] = true;
          publish(i);
          progressed = true;
        }
        if (initialised_[i] && s.step() < target && s.proposal_due()) {
          const StepProposal p = s.propose();
          for (std::size_t j = 0; j < n; ++j)
            if (j != i) steppers_[j]->add_proposal(i, s.step(), p);
          progressed = true;
        }
        if (initialised_[i] && s.step() < target && s.prediction_due()) {
          s.predict(prediction_);
          steppers_[index_of(nodes[i].cut->partner)]->add_partner_prediction(s.step(), prediction_);
          progressed = true;
        }
        if (initialised_[i] && s.step() < target && s.can_step()) {
          s.step(values_);
          publish(i);
          progressed = true;
        }
        all_there = all_there && initialised_[i] && (s.step() >= target || s.finished());
      }
      if (diverged_ || all_there) return;
      if (!progressed) throw std::logic_error("in-process run: deadlock");
    }
  }

  // The coupled state of all nodes (NodeStepper::coupled_state, node by node).
  std::vector<double> coupled_state() const {
    std::vector<double> z;
    for (const auto& s : steppers_) {
      const auto zi = s->coupled_state();
      z.insert(z.end(), zi.begin(), zi.end());
    }
    return z;
  }
  void set_coupled_state(std::vector<double> z) {
    // The two sides of an interface-Jacobian cut hold the same assumed torque (bit for bit,
    // checked by the solve): one coordinate, the "+" side's; the other side's copy follows it.
    for (std::size_t i = 0; i < steppers_.size(); ++i)
      if (const auto& cut = plan_->nodes()[i].cut; cut && cut->twist_sign < 0)
        z[torque_coordinate(i)] = z[torque_coordinate(index_of(cut->partner))];
    std::size_t at = 0;
    for (auto& s : steppers_) {
      const std::size_t m = s->coupled_state().size();
      s->set_coupled_state(std::span<const double>(z).subspan(at, m));
      at += m;
    }
  }
  // Coordinates that copy another (an interface-Jacobian cut's "-" side torque).
  std::vector<std::size_t> copied_coordinates() const {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < steppers_.size(); ++i)
      if (const auto& cut = plan_->nodes()[i].cut; cut && cut->twist_sign < 0) out.push_back(torque_coordinate(i));
    return out;
  }

 private:
  // The assumed torque is the last coordinate of a cut node's part.
  std::size_t torque_coordinate(std::size_t node) const {
    std::size_t at = 0;
    for (std::size_t i = 0; i <= node; ++i) at += steppers_[i]->coupled_state().size();
    return at - 1;
  }
  std::size_t index_of(const std::string& name) const {
    for (std::size_t i = 0; i < plan_->nodes().size(); ++i)
      if (plan_->nodes()[i].name() == name) return i;
    throw std::logic_error("no participant " + name);
  }
  void publish(std::size_t i) {
    auto& nodes = plan_->nodes();
    NodeStepper& s = *steppers_[i];
    const std::uint64_t k = s.step();
    if (auto why = guards_[i]->check(s.outputs())) diverged_ = "node '" + nodes[i].name() + "': " + *why;
    if (on_publish) on_publish(i, k, s.outputs());
    if (stiffness_ > 0 && energy_nodes_[i]) {
      const double t = s.outputs()[torque_output_[i]];
      if (energy_.size() <= k) energy_.resize(k + 1, 0.0);
      energy_[k] = std::max(energy_[k], std::isfinite(t) ? t * t / (2 * stiffness_) : 0.0);
    }
    for (const auto& [j, e] : readers_[i]) steppers_[j]->channel(e).add(k, values_);
  }

  std::unique_ptr<config::Scene> scene_;
  std::unique_ptr<ScenePlan> plan_;
  std::vector<std::unique_ptr<NodeStepper>> steppers_;
  std::vector<std::unique_ptr<DivergenceGuard>> guards_;
  std::vector<int> torque_output_;
  // Per node, the (reader node, its channel) pairs its published samples go to.
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> readers_;
  std::vector<bool> initialised_, energy_nodes_;
  std::vector<double> values_, prediction_, energy_;
  double stiffness_ = 0.0;
  std::optional<std::string> diverged_;
};

}  // namespace mechsim::cosim
