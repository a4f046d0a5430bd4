// The constants of the models and of the tools above them, defined once: the file-local
// copies each source kept (pi, two_pi, degree, rpm, inf, nan) collided in a unity build.
#pragma once

#include <limits>
#include <numbers>

namespace mechsim::models {

inline constexpr double pi = std::numbers::pi;
inline constexpr double two_pi = 2.0 * std::numbers::pi;
inline constexpr double degree = std::numbers::pi / 180.0;  // one degree in radians
inline constexpr double rpm = std::numbers::pi / 30.0;      // one revolution per minute in rad/s
inline constexpr double inf = std::numeric_limits<double>::infinity();
inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace mechsim::models
