// The bench's numbers as text: macro steps in the scene grammar, figures, tolerances, and
// JSON values that are null where a figure is not finite.
#pragma once

#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "json_io.h"

namespace mechsim::bench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// "250 us", "1 ms", "2.5 ms": exact enough for the scene grammar (9 significant digits).
std::string time_text(double s);
// A figure printed with `fmt`; "-" when not finite.
std::string num(double v, const char* fmt = "%.3g");
// A tolerance as "1e-3", "2.5e-4".
std::string tol_text(double v);
using tools::finite_or_null;  // json_io.h

}  // namespace mechsim::bench
