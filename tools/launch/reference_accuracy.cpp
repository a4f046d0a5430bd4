#include "reference_accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mechsim::launch {

nlohmann::json reference_accuracy_json(const config::Scene& scene, const cosim::ReferenceRun& ref,
                                       const cosim::ReferenceAccuracy& accuracy) {
  nlohmann::json signals = nlohmann::json::object();
  for (const auto& sig : scene.compare) {
    const std::string name = sig.full_name();
    const int c = ref.log.column(name);
    if (c < 0) continue;
    // Normalised like the co-simulation's errors (signal_compare.h): by the reference's range.
    const auto& r = ref.log.data[c];
    double lo = 0, hi = 0;
    if (!r.empty()) {
      auto [a, b] = std::minmax_element(r.begin(), r.end());
      lo = *a;
      hi = *b;
    }
    const double scale = hi > lo ? hi - lo : std::max(std::abs(hi), 1.0);
    const double max_abs = accuracy.max_abs_of(name), rms_abs = accuracy.rms_abs_of(name);
    signals[name] = {{"max_abs_difference", max_abs},
                     {"rms_abs_difference", rms_abs},
                     {"max_rel_difference", max_abs / scale},
                     {"rms_rel_difference", rms_abs / scale}};
  }
  return {{"method", "difference to a re-run at a 100x tighter tolerance"},
          {"rtol_check", accuracy.rtol},
          {"atol_check", accuracy.atol},
          {"wall_time_s", accuracy.wall_time_s},
          {"solver_steps", accuracy.stats.steps},
          {"signals", signals}};
}

void print_reference_accuracy(const nlohmann::json& accuracy) {
  std::printf("  reference error estimate (against rtol %g):\n", accuracy["rtol_check"].get<double>());
  for (auto& [name, e] : accuracy["signals"].items())
    std::printf("    %-32s max %.3g (%.3g %% of range), rms %.3g\n", name.c_str(), e["max_abs_difference"].get<double>(),
                100 * e["max_rel_difference"].get<double>(), e["rms_abs_difference"].get<double>());
}

}  // namespace mechsim::launch
