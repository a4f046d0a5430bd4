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

  std::uint64_t steps() const { return steps_; }  // n: instants 0 .. n
  double start() const { return t0_; }
  double end() const { return time(steps_); }
  double nominal_step() const { return h_; }
  bool uniform() const { return inserted_.empty() && moved_.empty(); }

  // t_k, for k in 0 .. steps(). A landed grid is kept as the uniform one plus its few
  // changes (never one double per step: a scene may have billions of steps).
  double time(std::uint64_t k) const { return uniform() ? uniform_time(k) : landed_time(k); }
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
  std::vector<std::uint64_t> event_steps_;  // ascending
};

}  // namespace mechsim::cosim
