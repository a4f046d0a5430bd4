#include "mechsim/assess/reference_comparison.h"

#include <span>
#include <stdexcept>

#include "mechsim/cosim/output_log.h"

namespace mechsim::assess {

ReferenceComparison compare_with_reference(const config::Scene& scene, const cosim::ScenePlan& plan, const std::string& run_dir) {
  ReferenceComparison out;
  // The monolithic reference on the macro-step grid (an adaptive run's: the instants its
  // nodes logged).
  cosim::ScenePlan reference_plan = cosim::ScenePlan::build(scene);
  out.reference = cosim::run_reference_at(reference_plan, cosim::run_instants(plan, run_dir));
  out.accuracy = cosim::estimate_reference_error(scene, out.reference);
  out.reference_accuracy = reference_signal_accuracy(scene, out.reference, out.accuracy);
  const cosim::ReferenceRun& ref = out.reference;
  std::map<std::string, cosim::OutputLog> logs;
  for (const auto& node : plan.nodes())
    logs[node.name()] = cosim::read_output_log(run_dir + "/" + node.name() + ".outputs.bin");
  // An adaptive step without time.scales measured each signal against its range so far,
  // small while it first rises: the ranges of this run, to write in the scene.
  if (const auto& a = scene.time.adaptive; a && a->scales.empty()) {
    auto& suggested = out.suggested_scales.emplace();
    for (const auto& [participant, field] : plan.scaled_quantities()) {
      const auto& log = logs.at(participant);
      const int c = log.column(field);
      if (c < 0) continue;
      if (const double range = cosim::finite_range(log.data[static_cast<std::size_t>(c)]); range > 0)
        suggested[participant][field] = range;
    }
  }
  out.t = ref.log.data[0];
  const std::span<const double> t = out.t;
  auto cosim_series = [&](const config::SignalRef& r) -> std::span<const double> {
    const auto& log = logs.at(r.participant);
    int c = log.column(r.output);
    return c < 0 ? std::span<const double>{} : std::span<const double>(log.data[c]);
  };
  auto reference_series = [&](const config::SignalRef& r) -> std::span<const double> {
    int c = ref.log.column(r.full_name());
    return c < 0 ? std::span<const double>{} : std::span<const double>(ref.log.data[c]);
  };
  for (const auto& sig : scene.compare) {
    auto c = cosim_series(sig);
    auto r = reference_series(sig);
    if (c.size() != r.size()) throw std::runtime_error(sig.full_name() + ": node log has " + std::to_string(c.size()) +
                                                       " rows, reference " + std::to_string(r.size()));
    const auto& node = plan.node(sig.participant);
    out.signals.push_back({sig, node.block->outputs()[node.block->output_index(sig.output)].unit,
                           std::vector<double>(c.begin(), c.end()), std::vector<double>(r.begin(), r.end()),
                           compare_signal(t, c, r), classify_error(t, c, r)});
  }
  const SeriesLookup reference_lookup = reference_series;
  out.report = report_figures(scene, t, cosim_series, &reference_lookup);
  for (const auto& e : ref.events) ++out.reference_event_counts[e.kind];
  for (const auto& node : plan.nodes())
    if (node.steps_itself) out.self_stepping.push_back(node.name());
  return out;
}

}  // namespace mechsim::assess
