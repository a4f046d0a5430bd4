#include "run_comparison.h"

#include <cstdio>
#include <map>
#include <span>
#include <stdexcept>

#include "csv.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/output_log.h"
#include "plot.h"
#include "realtime_report.h"
#include "reference_accuracy.h"
#include "run_report.h"
#include "signal_compare.h"
#include "solver_health.h"

namespace mechsim::launch {

using nlohmann::json;

void compare_with_reference(const config::Scene& scene, const cosim::ScenePlan& plan, const std::string& run_dir, bool plots,
                            json& summary) {
  // Compare with the monolithic reference on the macro-step grid (an adaptive run's: the
  // instants its nodes logged).
  cosim::ScenePlan reference_plan = cosim::ScenePlan::build(scene);
  cosim::ReferenceRun ref = cosim::run_reference_at(reference_plan, cosim::run_instants(plan, run_dir));
  const cosim::ReferenceAccuracy ref_accuracy = cosim::estimate_reference_error(scene, ref);
  std::map<std::string, cosim::OutputLog> logs;
  for (const auto& node : plan.nodes())
    logs[node.name()] = cosim::read_output_log(run_dir + "/" + node.name() + ".outputs.bin");
  // An adaptive step without time.scales measured each signal against its range so far,
  // small while it first rises: the ranges of this run, to write in the scene.
  if (const auto& a = scene.time.adaptive; a && a->scales.empty()) {
    json suggested = json::object();
    for (const auto& [participant, field] : plan.scaled_quantities()) {
      const auto& log = logs.at(participant);
      const int c = log.column(field);
      if (c < 0) continue;
      if (const double range = cosim::finite_range(log.data[static_cast<std::size_t>(c)]); range > 0)
        suggested[participant][field] = range;
    }
    summary["adaptive_step"]["suggested_scales"] = suggested;
  }
  const auto& t = ref.log.data[0];
  auto cosim_series = [&](const config::SignalRef& r) -> std::span<const double> {
    const auto& log = logs.at(r.participant);
    int c = log.column(r.output);
    return c < 0 ? std::span<const double>{} : std::span<const double>(log.data[c]);
  };
  auto reference_series = [&](const config::SignalRef& r) -> std::span<const double> {
    int c = ref.log.column(r.full_name());
    return c < 0 ? std::span<const double>{} : std::span<const double>(ref.log.data[c]);
  };
  json signals = json::object();
  std::vector<std::string> csv_header{"t"};
  std::vector<std::vector<double>> csv_columns{t};
  plot::Figure figure;
  figure.title = scene.name + ": co-simulation against the reference";
  for (const auto& sig : scene.compare) {
    auto c = cosim_series(sig);
    auto r = reference_series(sig);
    if (c.size() != r.size()) throw std::runtime_error(sig.full_name() + ": node log has " + std::to_string(c.size()) +
                                                       " rows, reference " + std::to_string(r.size()));
    SignalError e = compare_signal(t, c, r);
    const ErrorCause cause = classify_error(t, c, r);
    const auto& node = plan.node(sig.participant);
    signals[sig.full_name()] = {{"unit", node.block->outputs()[node.block->output_index(sig.output)].unit},
                                {"max_abs_error", e.max_abs}, {"max_rel_error", e.max_rel},
                                {"rms_abs_error", e.rms_abs}, {"rms_rel_error", e.rms_rel},
                                {"reference_range", e.range}, {"t_of_max_error_s", e.t_of_max},
                                {"finite", e.finite},
                                {"one_step_late", cause.one_step_late},
                                {"max_abs_error_shifted_one_step", cause.max_abs_shifted},
                                {"max_abs_error_at_jump", cause.jump},
                                {"t_jump_s", cause.jump ? json(cause.t_jump) : json(nullptr)},
                                {"reference_jumps", cause.jumps},
                                {"max_abs_error_away_from_jumps", cause.max_abs_away_from_jumps}};
    csv_header.push_back(sig.full_name());
    csv_columns.emplace_back(c.begin(), c.end());
    csv_header.push_back(sig.full_name() + ".reference");
    csv_columns.emplace_back(r.begin(), r.end());
    plot::Panel panel;
    panel.title = sig.full_name();
    panel.xlabel = "t [s]";
    panel.ylabel = sig.output + " [" + signals[sig.full_name()]["unit"].get<std::string>() + "]";
    panel.series.push_back({"reference", std::vector<double>(t.begin(), t.end()), std::vector<double>(r.begin(), r.end()), "lines"});
    panel.series.push_back({"co-simulation", std::vector<double>(t.begin(), t.end()), std::vector<double>(c.begin(), c.end()), "dashed"});
    figure.panels.push_back(panel);
    // At this scale the two curves lie on each other: the difference gets its own panel.
    plot::Panel error_panel;
    error_panel.title = sig.full_name() + ": co-simulation - reference";
    error_panel.xlabel = "t [s]";
    error_panel.ylabel = "error [" + signals[sig.full_name()]["unit"].get<std::string>() + "]";
    std::vector<double> difference(c.size());
    for (std::size_t k = 0; k < c.size(); ++k) difference[k] = c[k] - r[k];
    error_panel.series.push_back({"error", std::vector<double>(t.begin(), t.end()), std::move(difference), "lines"});
    figure.panels.push_back(error_panel);
  }
  summary["signals"] = signals;
  const SeriesLookup reference_lookup = reference_series;
  summary["report"] = report_figures(scene, t, cosim_series, &reference_lookup);
  json ref_events = json::object();
  for (const auto& e : ref.events) ref_events[e.kind] = ref_events.value(e.kind, 0) + 1;
  // What the errors are measured against: with a co-simulation FMU there is no monolithic
  // model of it, and the reference holds the FMU stepping itself as in the run.
  std::string self_stepping;
  for (const auto& node : plan.nodes())
    if (node.steps_itself) self_stepping += (self_stepping.empty() ? "" : ", ") + node.name();
  const std::string compared_with =
      self_stepping.empty()
          ? "the monolithic reference (every block of the scene in one ODE, integrated at tight tolerance)"
          : "the monolithic reference of the other blocks, with the co-simulation FMU(s) " + self_stepping +
                " stepping themselves inside it at their own step as in the run (there is no continuous model of a "
                "co-simulation FMU): the errors measure the coupling, not the FMU's own sampling";
  summary["reference"] = {{"compared_with", compared_with}, {"rtol", ref.rtol}, {"wall_time_s", ref.wall_time_s},
                          {"solver", solver_stats_json(ref.stats)},
                          {"event_counts", ref_events},
                          {"accuracy", reference_accuracy_json(scene, ref, ref_accuracy)}};
  tools::write_csv(run_dir + "/signals.csv", csv_header, csv_columns);
  summary["files"] = {{"signals_csv", run_dir + "/signals.csv"}};
  if (plots && !figure.panels.empty()) {
    std::string why;
    if (plot::write_png(figure, run_dir + "/signals.png", &why))
      summary["files"]["signals_png"] = run_dir + "/signals.png";
    else
      std::fprintf(stderr, "mechsim: no plot: %s\n", why.c_str());
  }
}

void plot_lateness(const config::Scene& scene, const std::string& run_dir, json& summary) {
  std::string why;
  const auto pngs = write_lateness_plots(summary["realtime"], scene.time.step / scene.rtf, run_dir, &why);
  for (const auto& png : pngs) summary["files"]["lateness_png"].push_back(png);
  if (pngs.empty() && !why.empty()) std::fprintf(stderr, "mechsim: no lateness plot: %s\n", why.c_str());
}

}  // namespace mechsim::launch
