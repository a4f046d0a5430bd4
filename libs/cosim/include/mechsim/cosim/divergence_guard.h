// Detects a co-simulation that has gone numerically unstable, so that a macro step beyond
// the stability limit of its coupling stops the run instead of producing garbage.
//
// Criteria on a node's published outputs:
//  - any value non-finite;
//  - a growing oscillation: the swing (max - min) of a value over consecutive windows of
//    `window` steps grows window after window while the value keeps turning back and forth
//    (at least two local extrema per window):
//      fast: by more than 2x per window, 8 windows in a row;
//      slow: measured over blocks of 5 windows (which smooths beats between modes), by
//            more than 2 % per block, 15 blocks in a row, 4x in all.
//    An unstable coupling mode is oscillatory and grows geometrically, from fast (far
//    beyond the limit) to very slow (just beyond it). Physical transients either stop
//    growing (steps, resonances of a stable system) or do not oscillate (ramps, start-up).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mechsim::cosim {

class DivergenceGuard {
 public:
  explicit DivergenceGuard(std::vector<std::string> names, int window = 20, double floor = 1e-12);
  // Call once per published step; returns why the run diverged, if it did.
  std::optional<std::string> check(std::span<const double> values);
  // Its whole history as numbers, for a node's checkpoint (checkpoint.h): a rolled-back
  // run judges divergence exactly as an undisturbed one.
  std::vector<double> save() const;
  void restore(std::span<const double> saved);  // throws std::invalid_argument on a size mismatch

 private:
  struct Track {
    double lo = 0, hi = 0, last_swing = 0, previous = 0, previous_diff = 0;
    int extrema = 0, fast_streak = 0;
    // slow criterion: swing and oscillation over the current block of windows
    double block_swing = 0, last_block_swing = 0, slow_growth = 1.0;
    int block_windows = 0, block_oscillating = 0, slow_streak = 0;
  };
  std::vector<std::string> names_;
  int window_;
  double floor_;
  int in_window_ = 0;
  long seen_ = 0;
  std::vector<Track> tracks_;
};

}  // namespace mechsim::cosim
