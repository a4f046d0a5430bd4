#include "mechsim/assess/reference_accuracy.h"

#include "mechsim/assess/signal_compare.h"

namespace mechsim::assess {

std::vector<SignalAccuracy> reference_signal_accuracy(const config::Scene& scene, const cosim::ReferenceRun& ref,
                                                      const cosim::ReferenceAccuracy& accuracy) {
  std::vector<SignalAccuracy> out;
  for (const auto& sig : scene.compare) {
    const std::string name = sig.full_name();
    const int c = ref.log.column(name);
    if (c < 0) continue;
    const double scale = relative_scale(ref.log.data[c]);
    const double max_abs = accuracy.max_abs_of(name), rms_abs = accuracy.rms_abs_of(name);
    out.push_back({name, max_abs, rms_abs, max_abs / scale, rms_abs / scale});
  }
  return out;
}

}  // namespace mechsim::assess
