#include "run_report.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mechsim::launch {

nlohmann::json report_extrema(const config::Scene& scene, std::span<const double> t, const SeriesLookup& series) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& r : scene.report) {
    auto values = series(r.signal);
    if (values.empty()) continue;
    auto it = r.stat == "min" ? std::min_element(values.begin(), values.end())
                              : std::max_element(values.begin(), values.end());
    const std::size_t i = static_cast<std::size_t>(it - values.begin());
    nlohmann::json entry{{"stat", r.stat}, {"signal", r.signal.full_name()}, {"value", *it}, {"t_s", t[i]}};
    if (r.at) {
      double v = series(*r.at)[i];
      if (r.at_wrap_turn) v = std::fmod(std::fmod(v, 2 * std::numbers::pi) + 2 * std::numbers::pi, 2 * std::numbers::pi);
      entry["at"] = {{"signal", r.at->full_name()}, {"value", v / r.at_scale}, {"unit", r.at_unit.empty() ? "SI" : r.at_unit}};
    }
    out.push_back(entry);
  }
  return out;
}

nlohmann::json solver_stats_json(const solve::SolverStats& s) {
  return {{"steps", s.steps},
          {"rhs_evals", s.rhs_evals},
          {"error_test_failures", s.error_test_failures},
          {"nonlinear_failures", s.nonlinear_failures},
          {"jacobian_evals", s.jacobian_evals},
          {"roots_found", s.roots_found},
          {"restarts", s.restarts},
          {"last_step_s", s.last_step},
          {"last_order", s.last_order}};
}

}  // namespace mechsim::launch
