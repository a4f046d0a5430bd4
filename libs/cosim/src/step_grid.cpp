#include "mechsim/cosim/step_grid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace mechsim::cosim {

StepGrid::StepGrid(const config::TimeSpec& time)
    : t0_(time.start), h_(time.step), steps_(static_cast<std::uint64_t>(time.steps())) {
  if (!(h_ > 0)) throw std::invalid_argument("StepGrid: the macro step must be positive");
}

StepGrid StepGrid::landing_on(const config::TimeSpec& time, std::span<const double> events, double snap) {
  StepGrid grid(time);
  std::vector<double> extra;
  // An event within snap H of a uniform instant takes that instant's place (it is a few
  // ulps away at most, and the event's own double is the first on its far side).
  std::map<std::uint64_t, double> moved;
  for (double e : events) {
    if (!std::isfinite(e) || e <= grid.start() || e >= grid.end()) continue;
    const auto below = static_cast<std::uint64_t>(std::floor((e - grid.t0_) / grid.h_));
    // Rounding in the division may put `below` one off; the nearest uniform instant decides.
    bool on_instant = false;
    for (std::uint64_t j : {below == 0 ? 0 : below - 1, below, below + 1})
      if (j > 0 && j < grid.steps_ && std::abs(e - grid.time(j)) < snap * grid.h_) {
        on_instant = true;
        auto [it, added] = moved.emplace(j, e);
        if (!added) it->second = std::min(it->second, e);
        break;
      }
    if (!on_instant) extra.push_back(e);
  }
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end(), [&](double a, double b) { return b - a < snap * grid.h_; }),
              extra.end());
  const bool stays_uniform =
      extra.empty() && std::all_of(moved.begin(), moved.end(), [&](const auto& m) { return m.second == grid.time(m.first); });
  if (stays_uniform) {
    for (const auto& m : moved) grid.event_steps_.push_back(m.first);
    return grid;
  }
  std::vector<double> instants;
  instants.reserve(grid.steps_ + 1 + extra.size());
  auto next_event = extra.begin();
  for (std::uint64_t j = 0; j <= grid.steps_; ++j) {
    const auto replaced = moved.find(j);
    const double t = replaced == moved.end() ? grid.time(j) : replaced->second;
    while (next_event != extra.end() && *next_event < t) {
      grid.event_steps_.push_back(instants.size());
      instants.push_back(*next_event++);
    }
    if (replaced != moved.end()) grid.event_steps_.push_back(instants.size());
    instants.push_back(t);
  }
  grid.instants_ = std::move(instants);
  grid.steps_ = grid.instants_.size() - 1;
  return grid;
}

std::optional<std::uint64_t> StepGrid::step_at(double t) const {
  if (instants_.empty()) {
    const double k = std::round((t - t0_) / h_);
    if (!(k >= 0) || k > static_cast<double>(steps_)) return std::nullopt;
    const auto step = static_cast<std::uint64_t>(k);
    if (time(step) != t) return std::nullopt;
    return step;
  }
  const auto it = std::lower_bound(instants_.begin(), instants_.end(), t);
  if (it == instants_.end() || *it != t) return std::nullopt;
  return static_cast<std::uint64_t>(it - instants_.begin());
}

}  // namespace mechsim::cosim
