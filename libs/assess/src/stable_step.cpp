#include "mechsim/assess/stable_step.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mechsim/catalog/coupling/coupling_spec.h"

namespace mechsim::assess {

// The overrides that put the scene at macro step h: the step, and every participant
// sampled at the scene's own macro step sampled at h too (a sampled amplifier, identical
// in the reference: coupling-facts.md).
std::vector<std::string> at_macro_step(const config::Scene& base, double h, std::vector<std::string> overrides) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g s", h);
  overrides.push_back(std::string("time.step=") + buf);
  // A whole number of steps: the run ends at the first step boundary at or after the
  // scene's end, and lasts at least kMinSteps steps (the divergence guard's slow criterion
  // needs 1500 steps to see a mode that grows by a few per mille per step).
  const double n = std::max(std::ceil((base.time.end - base.time.start) / h - 1e-9), static_cast<double>(kMinSteps));
  char end[64];
  std::snprintf(end, sizeof end, "%.17g s", base.time.start + n * h);
  overrides.push_back(std::string("time.end=") + end);
  for (const auto& p : base.participants)
    if (p.params.has("sample_time")) {
      const double ts = p.params.child("sample_time").as_quantity(config::dim::time);
      if (std::abs(ts - base.time.step) < 1e-12 * base.time.step)
        overrides.push_back("participants." + p.name + ".params.sample_time=" + buf);
    }
  return overrides;
}

StepTrial try_macro_step(const std::string& path, const config::Scene& base, const std::vector<std::string>& overrides,
                         double h, const std::string& a, const std::string& b, double stiffness) {
  cosim::SteppedRun run(path, at_macro_step(base, h, overrides));
  run.watch_energy(a, b, stiffness);
  StepTrial t;
  try {
    run.advance(run.steps());
  } catch (const std::exception& e) {
    // A solver that fails (step size underflow on an exploding state) is unstable too.
    return {false, std::string("solver failed: ") + e.what()};
  }
  if (run.diverged()) return {false, *run.diverged()};
  const auto& e = run.energy();
  if (e.size() >= 20) {
    const std::size_t tail = e.size() - e.size() / 10;
    const double before = *std::max_element(e.begin(), e.begin() + static_cast<long>(tail));
    const double after = *std::max_element(e.begin() + static_cast<long>(tail), e.end());
    const double peak = std::max(before, after);
    if (after > 4 * before && after > 1e-6 * peak) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "coupling spring energy grows: %.3g J in the last tenth of the run, %.3g J before", after, before);
      return {false, buf};
    }
  }
  return t;
}

std::optional<double> find_stable_step_below(const std::string& path, const std::vector<std::string>& overrides, double h,
                                             int halvings) {
  const config::Scene base = config::load_scene(path, overrides);
  std::string a, b;
  double stiffness = 0.0;
  for (const auto& c : base.connections)
    if (c.coupling && stiffness <= 0) {
      stiffness = cosim::coupling::parse_coupling(*c.coupling).params.stiffness;
      a = c.from;
      b = c.to;
    }
  for (int i = 0; i < halvings; ++i) {
    h /= 2;
    if (try_macro_step(path, base, overrides, h, a, b, stiffness).stable) return h;
  }
  return std::nullopt;
}

}  // namespace mechsim::assess
