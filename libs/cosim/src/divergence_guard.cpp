#include "mechsim/cosim/divergence_guard.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mechsim::cosim {

namespace {
constexpr double kFastGrowth = 2.0;
constexpr int kFastWindows = 8;
constexpr int kBlockWindows = 5;
constexpr double kSlowGrowth = 1.02;
constexpr int kSlowBlocks = 15;
constexpr double kSlowTotal = 4.0;
}  // namespace

DivergenceGuard::DivergenceGuard(std::vector<std::string> names, int window, double floor)
    : names_(std::move(names)), window_(window), floor_(floor), tracks_(names_.size()) {}

std::vector<double> DivergenceGuard::save() const {
  std::vector<double> z{static_cast<double>(in_window_), static_cast<double>(seen_)};
  for (const Track& t : tracks_)
    z.insert(z.end(), {t.lo, t.hi, t.last_swing, t.previous, t.previous_diff, static_cast<double>(t.extrema),
                       static_cast<double>(t.fast_streak), t.block_swing, t.last_block_swing, t.slow_growth,
                       static_cast<double>(t.block_windows), static_cast<double>(t.block_oscillating),
                       static_cast<double>(t.slow_streak)});
  return z;
}

void DivergenceGuard::restore(std::span<const double> z) {
  constexpr std::size_t kPerTrack = 13;
  if (z.size() != 2 + kPerTrack * tracks_.size()) throw std::invalid_argument("divergence guard: saved state has the wrong size");
  in_window_ = static_cast<int>(z[0]);
  seen_ = static_cast<long>(z[1]);
  std::size_t i = 2;
  for (Track& t : tracks_) {
    t.lo = z[i++], t.hi = z[i++], t.last_swing = z[i++], t.previous = z[i++], t.previous_diff = z[i++];
    t.extrema = static_cast<int>(z[i++]), t.fast_streak = static_cast<int>(z[i++]);
    t.block_swing = z[i++], t.last_block_swing = z[i++], t.slow_growth = z[i++];
    t.block_windows = static_cast<int>(z[i++]), t.block_oscillating = static_cast<int>(z[i++]), t.slow_streak = static_cast<int>(z[i++]);
  }
}

std::optional<std::string> DivergenceGuard::check(std::span<const double> values) {
  const bool first_in_window = in_window_ == 0;
  for (std::size_t i = 0; i < values.size() && i < tracks_.size(); ++i) {
    const double v = values[i];
    if (!std::isfinite(v)) return "output '" + names_[i] + "' is not finite";
    Track& tr = tracks_[i];
    if (first_in_window) tr.lo = tr.hi = v;
    tr.lo = std::min(tr.lo, v);
    tr.hi = std::max(tr.hi, v);
    const double diff = v - tr.previous;
    if (seen_ > 1 && diff * tr.previous_diff < 0) ++tr.extrema;
    if (diff != 0) tr.previous_diff = diff;
    tr.previous = v;
  }
  ++seen_;
  if (++in_window_ < window_) return std::nullopt;
  in_window_ = 0;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    Track& tr = tracks_[i];
    const double swing = tr.hi - tr.lo;
    const bool oscillating = tr.extrema >= 2 && swing > floor_;
    const double ratio = tr.last_swing > 0 ? swing / tr.last_swing : 0.0;
    tr.fast_streak = oscillating && ratio > kFastGrowth ? tr.fast_streak + 1 : 0;
    tr.block_swing = std::max(tr.block_swing, swing);
    tr.block_oscillating += oscillating ? 1 : 0;
    if (++tr.block_windows == kBlockWindows) {
      const double block_ratio = tr.last_block_swing > 0 ? tr.block_swing / tr.last_block_swing : 0.0;
      if (tr.block_oscillating == kBlockWindows && block_ratio > kSlowGrowth) {
        ++tr.slow_streak;
        tr.slow_growth *= block_ratio;
      } else {
        tr.slow_streak = 0;
        tr.slow_growth = 1.0;
      }
      tr.last_block_swing = tr.block_swing;
      tr.block_swing = 0;
      tr.block_windows = tr.block_oscillating = 0;
    }
    tr.extrema = 0;
    tr.last_swing = swing;
    const bool fast = tr.fast_streak >= kFastWindows;
    const bool slow = tr.slow_streak >= kSlowBlocks && tr.slow_growth >= kSlowTotal;
    if (fast || slow) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "output '%s' oscillates with a swing growing %s for %d windows of %d steps (now %.3g)",
                    names_[i].c_str(), fast ? "more than 2x per window" : "steadily",
                    fast ? tr.fast_streak : tr.slow_streak * kBlockWindows, window_, swing);
      return std::string(buf);
    }
  }
  return std::nullopt;
}

}  // namespace mechsim::cosim
