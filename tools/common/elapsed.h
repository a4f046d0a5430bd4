// Wall time elapsed since a steady-clock instant, in seconds (timeouts, progress, reports).
#pragma once

#include <chrono>

namespace mechsim {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace mechsim
