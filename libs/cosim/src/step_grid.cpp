#include "mechsim/cosim/step_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mechsim::cosim {

StepGrid::StepGrid(const config::TimeSpec& time)
    : t0_(time.start), h_(time.step), steps_(static_cast<std::uint64_t>(time.steps())) {
  if (!(h_ > 0)) throw std::invalid_argument("StepGrid: the macro step must be positive");
}

StepGrid StepGrid::landing_on(const config::TimeSpec& time, std::span<const double> events, double snap) {
  StepGrid grid(time);
  std::vector<double> extra;
  for (double e : events) {
    if (!std::isfinite(e) || e <= grid.start() || e >= grid.end()) continue;
    const auto below = static_cast<std::uint64_t>(std::floor((e - grid.t0_) / grid.h_));
    // Rounding in the division may put `below` one off; the nearest uniform instant decides.
    bool on_instant = false;
    for (std::uint64_t j : {below == 0 ? 0 : below - 1, below, below + 1})
      if (j <= grid.steps_ && std::abs(e - grid.time(j)) < snap * grid.h_) on_instant = true;
    if (!on_instant) extra.push_back(e);
  }
  if (extra.empty()) return grid;
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end(), [&](double a, double b) { return b - a < snap * grid.h_; }),
              extra.end());
  std::vector<double> instants;
  instants.reserve(grid.steps_ + 1 + extra.size());
  auto next_event = extra.begin();
  for (std::uint64_t j = 0; j <= grid.steps_; ++j) {
    const double t = grid.time(j);
    while (next_event != extra.end() && *next_event < t) instants.push_back(*next_event++);
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
