// Test helper: figures of a step response. The in-process run itself is
// mechsim/cosim/stepped_run.h.
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
