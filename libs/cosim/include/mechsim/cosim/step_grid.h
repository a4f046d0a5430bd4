// The macro-step instants of a run, t_0 .. t_n: one answer to "when is step k" for every
// node, the reference, the replay, the pacer and the tools, so that all of them agree to
// the bit.
//
// A uniform grid is t_k = t0 + k H, computed from k and never accumulated (so a node that
// restarts at step K, a replay and the reference get the same instants as the run). A grid
// that lands on events (landing_on) keeps those instants and adds each event as a boundary
// of its own: the step before it ends on the event, the next one runs to the following
// uniform instant. The scene plan lands its grid on what the participants schedule before
// the run (ScenePlan::grid, docs/accuracy.md "Discontinuities").
//
// An adaptive grid (time.step: adaptive) knows t_0 only at the start and grows by one
// instant each time the nodes agree on a step (StepAgreement, step_control.h): extend().
// Its instants, once set, never change, so a reader that saw t_k sees the same t_k ever
// after; it holds one double per step taken (at most 1e8, the scene parser's bound).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "mechsim/config/scene.h"

namespace mechsim::cosim {

class StepGrid {
 public:
  // The uniform grid of a scene's time section.
  explicit StepGrid(const config::TimeSpec& time);
  // The uniform grid with every event strictly inside (start, end) a boundary of its own.
  // An event closer to a uniform instant than `snap` (a fraction of H) takes that instant's
  // place (no step shorter than snap H is made; the instant moves by a few ulps so that it
  // is the event's own double, the first on the event's far side). Events need not be
  // sorted; duplicates merge.
  static StepGrid landing_on(const config::TimeSpec& time, std::span<const double> events, double snap = 1e-6);
  // An adaptive grid from t_0 to the end, with the discontinuities the participants
  // scheduled before the run (sorted here): the agreement lands steps on them.
  static StepGrid adaptive(const config::TimeSpec& time, std::vector<double> events);

  // n: instants 0 .. n. Adaptive: the instants agreed so far (all of them once at the end).
  std::uint64_t steps() const { return adaptive_ ? times_.size() - 1 : steps_; }
  double start() const { return t0_; }
  double end() const { return adaptive_ ? end_ : time(steps_); }
  // H of a fixed-step grid; an adaptive grid's largest step (time.adaptive.max).
  double nominal_step() const { return h_; }
  bool uniform() const { return !adaptive_ && inserted_.empty() && moved_.empty(); }
  bool is_adaptive() const { return adaptive_; }
  // The scene's time.step: adaptive settings (adaptive grid only).
  const config::AdaptiveStepSpec& adaptive_spec() const { return adaptive_spec_; }
  // True when t_k is the run's end (the node that published step k is done).
  bool at_end(std::uint64_t k) const { return adaptive_ ? k < times_.size() && times_[k] >= end_ : k >= steps_; }
  // Adaptive: sets t_k+1 (the agreed end of step k -> k+1; `event`: it is a discontinuity's
  // instant). Setting it again to the same value is allowed (nodes that share one grid in a
  // process each extend it); another value, or a step not next to the known ones, throws
  // std::logic_error. Logically const: it only adds instants (see the file comment).
  void extend(std::uint64_t k, double t_next, bool event) const;
  // Adaptive: true when t_k+1 is known.
  bool knows_end_of(std::uint64_t k) const { return !adaptive_ || k + 1 < times_.size(); }
  // The first scheduled discontinuity after t (strictly), +inf when none: what an adaptive
  // step lands on.
  double next_scheduled_event(double t) const;

  // t_k, for k in 0 .. steps(). A landed grid is kept as the uniform one plus its few
  // changes (never one double per step: a scene may have billions of steps).
  double time(std::uint64_t k) const {
    if (adaptive_) return times_.at(k);
    return uniform() ? uniform_time(k) : landed_time(k);
  }
  // t_k+1 - t_k; on a uniform grid H itself (not the difference, which may round).
  double step_length(std::uint64_t k) const { return uniform() ? h_ : time(k + 1) - time(k); }
  // The step whose instant is t (as computed by time(k)); nullopt when t is no instant.
  std::optional<std::uint64_t> step_at(double t) const;
  // True when t_k is one of the events the grid landed on (inserted, or a uniform instant
  // the event fell on): what a node logs at t_k is then its value after the event.
  bool is_event(std::uint64_t k) const {
    return !event_steps_.empty() && std::binary_search(event_steps_.begin(), event_steps_.end(), k);
  }
  std::size_t event_count() const { return event_steps_.size(); }

 private:
  double uniform_time(std::uint64_t j) const { return t0_ + static_cast<double>(j) * h_; }
  double landed_time(std::uint64_t k) const;
  double t0_, h_;
  std::uint64_t uniform_steps_;  // of the scene's uniform grid
  std::uint64_t steps_;          // uniform_steps_ + inserted events
  std::vector<double> inserted_;          // events between uniform instants, ascending
  std::vector<std::uint64_t> inserted_at_;  // their step indices
  std::vector<std::pair<std::uint64_t, double>> moved_;  // (uniform index, event time in its place), ascending
  mutable std::vector<std::uint64_t> event_steps_;  // ascending (adaptive: grows with the grid)
  // Adaptive grid: the agreed instants, the end, the scheduled discontinuities (ascending).
  bool adaptive_ = false;
  config::AdaptiveStepSpec adaptive_spec_;
  double end_ = 0.0;
  mutable std::vector<double> times_;
  std::vector<double> scheduled_;
};

}  // namespace mechsim::cosim
