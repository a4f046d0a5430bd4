#include "run_report.h"

#include <algorithm>
#include <vector>

namespace mechsim::launch {

using nlohmann::json;

json solver_stats_json(const solve::SolverStats& s) {
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

nlohmann::json adaptive_step_summary(const config::AdaptiveStepSpec& spec, std::span<const double> instants) {
  nlohmann::json a = {{"tolerance", spec.tolerance}, {"min_s", spec.min}, {"max_s", spec.max}, {"initial_s", spec.initial},
                      {"steps", instants.empty() ? 0 : instants.size() - 1}, {"shortest_s", nullptr}, {"longest_s", nullptr},
                      {"median_s", nullptr}};
  if (instants.size() < 2) return a;
  std::vector<double> h(instants.size() - 1);
  for (std::size_t k = 0; k + 1 < instants.size(); ++k) h[k] = instants[k + 1] - instants[k];
  std::sort(h.begin(), h.end());
  a["shortest_s"] = h.front();
  a["longest_s"] = h.back();
  a["median_s"] = h[h.size() / 2];
  return a;
}

}  // namespace mechsim::launch
