#include "mechsim/cosim/step_grid.h"

#include "mechsim/cosim/step_control.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace mechsim::cosim {

StepGrid::StepGrid(const config::TimeSpec& time)
    : t0_(time.start), h_(time.step),
      uniform_steps_(time.adaptive ? 0 : static_cast<std::uint64_t>(time.steps())), steps_(uniform_steps_) {
  if (!(h_ > 0)) throw std::invalid_argument("StepGrid: the macro step must be positive");
}

StepGrid StepGrid::adaptive(const config::TimeSpec& time, std::vector<double> events) {
  StepGrid grid(time);
  grid.adaptive_ = true;
  grid.adaptive_spec_ = *time.adaptive;
  grid.end_ = time.end;
  grid.times_.assign(1, time.start);
  // Events closer together than the smallest step are one (the latest of them: each is the
  // first double on its own far side, so the latest is past all of them); no sliver steps.
  std::sort(events.begin(), events.end());
  for (double e : events) {
    if (!std::isfinite(e) || e <= time.start || e >= time.end) continue;
    if (!grid.scheduled_.empty() && e - grid.scheduled_.back() < grid.adaptive_spec_.min) grid.scheduled_.back() = e;
    else grid.scheduled_.push_back(e);
  }
  // The first step: `initial`, landed like every other (the nodes' proposals set the later ones).
  const double first_event = grid.next_scheduled_event(time.start);
  const AgreedStep first = end_of_step(time.start, grid.adaptive_spec_.initial, first_event, std::isfinite(first_event),
                                       grid.adaptive_spec_, time.end);
  grid.extend(0, first.t_next, first.event);
  return grid;
}

void StepGrid::extend(std::uint64_t k, double t_next, bool event) const {
  if (!adaptive_) throw std::logic_error("StepGrid::extend on a fixed-step grid");
  if (k + 1 < times_.size()) {
    if (times_[k + 1] != t_next) throw std::logic_error("step grid: step " + std::to_string(k) + " agreed twice with different ends");
    return;
  }
  if (k + 1 != times_.size()) throw std::logic_error("step grid: step " + std::to_string(k) + " agreed before the step before it");
  if (!(t_next > times_.back()) || t_next > end_) throw std::logic_error("step grid: step " + std::to_string(k) + " does not go forward");
  times_.push_back(t_next);
  if (event) event_steps_.push_back(k + 1);
}

double StepGrid::next_scheduled_event(double t) const {
  const auto it = std::upper_bound(scheduled_.begin(), scheduled_.end(), t);
  return it == scheduled_.end() ? HUGE_VAL : *it;
}

StepGrid StepGrid::landing_on(const config::TimeSpec& time, std::span<const double> events, double snap) {
  StepGrid grid(time);
  std::vector<double> extra;
  // An event within snap H of a uniform instant takes that instant's place (it is a few
  // ulps away at most, and the event's own double is the first on its far side).
  std::map<std::uint64_t, double> on_instant;
  for (double e : events) {
    if (!std::isfinite(e) || e <= grid.start() || e >= grid.end()) continue;
    const double j_real = std::floor((e - grid.t0_) / grid.h_);
    const auto below = static_cast<std::uint64_t>(std::max(0.0, j_real));
    // Rounding in the division may put `below` one off; the nearest uniform instant decides.
    bool snapped = false;
    for (std::uint64_t j : {below == 0 ? 0 : below - 1, below, below + 1})
      if (j > 0 && j < grid.uniform_steps_ && std::abs(e - grid.uniform_time(j)) < snap * grid.h_) {
        snapped = true;
        auto [it, added] = on_instant.emplace(j, e);
        if (!added) it->second = std::min(it->second, e);
        break;
      }
    if (!snapped) extra.push_back(e);
  }
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end(), [&](double a, double b) { return b - a < snap * grid.h_; }),
              extra.end());
  for (const auto& [j, e] : on_instant)
    if (e != grid.uniform_time(j)) grid.moved_.emplace_back(j, e);
  // Each inserted event's index: the uniform instants before it, plus the events before it.
  for (std::size_t i = 0; i < extra.size(); ++i) {
    const double e = extra[i];
    auto j = static_cast<std::uint64_t>(std::max(0.0, std::floor((e - grid.t0_) / grid.h_)));
    while (j + 1 <= grid.uniform_steps_ && grid.uniform_time(j + 1) < e) ++j;
    while (j > 0 && grid.uniform_time(j) >= e) --j;
    grid.inserted_.push_back(e);
    grid.inserted_at_.push_back(j + 1 + i);  // instants 0..j come first, then i events
  }
  grid.steps_ = grid.uniform_steps_ + grid.inserted_.size();
  // Event steps: the inserted ones, and the uniform instants events fell on, shifted by the
  // inserted events before them.
  grid.event_steps_ = grid.inserted_at_;
  for (const auto& [j, e] : on_instant) {
    const auto before = static_cast<std::uint64_t>(std::lower_bound(grid.inserted_.begin(), grid.inserted_.end(), e) -
                                                   grid.inserted_.begin());
    grid.event_steps_.push_back(j + before);
  }
  std::sort(grid.event_steps_.begin(), grid.event_steps_.end());
  return grid;
}

double StepGrid::landed_time(std::uint64_t k) const {
  const auto it = std::lower_bound(inserted_at_.begin(), inserted_at_.end(), k);
  if (it != inserted_at_.end() && *it == k) return inserted_[static_cast<std::size_t>(it - inserted_at_.begin())];
  const std::uint64_t j = k - static_cast<std::uint64_t>(it - inserted_at_.begin());  // the uniform instant
  const auto moved = std::lower_bound(moved_.begin(), moved_.end(), std::pair<std::uint64_t, double>{j, -HUGE_VAL});
  if (moved != moved_.end() && moved->first == j) return moved->second;
  return uniform_time(j);
}

std::optional<std::uint64_t> StepGrid::step_at(double t) const {
  if (!std::isfinite(t)) return std::nullopt;
  if (adaptive_) {
    const auto it = std::lower_bound(times_.begin(), times_.end(), t);
    if (it == times_.end() || *it != t) return std::nullopt;
    return static_cast<std::uint64_t>(it - times_.begin());
  }
  if (const auto it = std::lower_bound(inserted_.begin(), inserted_.end(), t); it != inserted_.end() && *it == t)
    return inserted_at_[static_cast<std::size_t>(it - inserted_.begin())];
  const double j_real = std::round((t - t0_) / h_);
  if (!(j_real >= 0) || j_real > static_cast<double>(uniform_steps_)) return std::nullopt;
  const auto j = static_cast<std::uint64_t>(j_real);
  const auto before = static_cast<std::uint64_t>(std::lower_bound(inserted_.begin(), inserted_.end(), t) - inserted_.begin());
  if (time(j + before) != t) return std::nullopt;
  return j + before;
}

}  // namespace mechsim::cosim
