#include "mechsim/cosim/step_grid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace mechsim::cosim {

StepGrid::StepGrid(const config::TimeSpec& time)
    : t0_(time.start), h_(time.step), uniform_steps_(static_cast<std::uint64_t>(time.steps())), steps_(uniform_steps_) {
  if (!(h_ > 0)) throw std::invalid_argument("StepGrid: the macro step must be positive");
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
