#include "run_comparison.h"

#include <cstdio>

#include "assessment_json.h"
#include "csv.h"
#include "plot.h"
#include "realtime_report.h"
#include "run_report.h"

namespace mechsim::launch {

using nlohmann::json;

namespace {

json signal_json(const assess::ComparedSignal& s) {
  const assess::SignalError& e = s.error;
  const assess::ErrorCause& cause = s.cause;
  return {{"unit", s.unit},
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
}

// Each signal against the reference, and below it their difference: at the scale of the
// signal the two curves lie on each other.
plot::Figure signals_figure(const config::Scene& scene, const assess::ReferenceComparison& cmp) {
  plot::Figure figure;
  figure.title = scene.name + ": co-simulation against the reference";
  for (const auto& s : cmp.signals) {
    const std::string name = s.signal.full_name();
    plot::Panel panel;
    panel.title = name;
    panel.xlabel = "t [s]";
    panel.ylabel = s.signal.output + " [" + s.unit + "]";
    panel.series.push_back({"reference", cmp.t, s.reference, "lines"});
    panel.series.push_back({"co-simulation", cmp.t, s.cosim, "dashed"});
    figure.panels.push_back(panel);
    plot::Panel error_panel;
    error_panel.title = name + ": co-simulation - reference";
    error_panel.xlabel = "t [s]";
    error_panel.ylabel = "error [" + s.unit + "]";
    std::vector<double> difference(s.cosim.size());
    for (std::size_t k = 0; k < s.cosim.size(); ++k) difference[k] = s.cosim[k] - s.reference[k];
    error_panel.series.push_back({"error", cmp.t, std::move(difference), "lines"});
    figure.panels.push_back(error_panel);
  }
  return figure;
}

}  // namespace

void write_comparison(const config::Scene& scene, const assess::ReferenceComparison& cmp, const std::string& run_dir,
                      bool plots, json& summary) {
  if (cmp.suggested_scales) {
    json suggested = json::object();
    for (const auto& [participant, fields] : *cmp.suggested_scales)
      for (const auto& [field, range] : fields) suggested[participant][field] = range;
    summary["adaptive_step"]["suggested_scales"] = suggested;
  }
  json signals = json::object();
  std::vector<std::string> csv_header{"t"};
  std::vector<std::vector<double>> csv_columns{cmp.t};
  for (const auto& s : cmp.signals) {
    const std::string name = s.signal.full_name();
    signals[name] = signal_json(s);
    csv_header.push_back(name);
    csv_columns.push_back(s.cosim);
    csv_header.push_back(name + ".reference");
    csv_columns.push_back(s.reference);
  }
  summary["signals"] = signals;
  summary["report"] = tools::report_figures_json(cmp.report);
  json ref_events = json::object();
  for (const auto& [kind, count] : cmp.reference_event_counts) ref_events[kind] = count;
  // What the errors are measured against: with a co-simulation FMU there is no monolithic
  // model of it, and the reference holds the FMU stepping itself as in the run.
  std::string self_stepping;
  for (const auto& name : cmp.self_stepping) self_stepping += (self_stepping.empty() ? "" : ", ") + name;
  const std::string compared_with =
      self_stepping.empty()
          ? "the monolithic reference (every block of the scene in one ODE, integrated at tight tolerance)"
          : "the monolithic reference of the other blocks, with the co-simulation FMU(s) " + self_stepping +
                " stepping themselves inside it at their own step as in the run (there is no continuous model of a "
                "co-simulation FMU): the errors measure the coupling, not the FMU's own sampling";
  const cosim::ReferenceRun& ref = cmp.reference;
  summary["reference"] = {{"compared_with", compared_with}, {"rtol", ref.rtol}, {"wall_time_s", ref.wall_time_s},
                          {"solver", solver_stats_json(ref.stats)},
                          {"event_counts", ref_events},
                          {"accuracy", tools::reference_accuracy_json(cmp.accuracy, cmp.reference_accuracy)}};
  tools::write_csv(run_dir + "/signals.csv", csv_header, csv_columns);
  summary["files"] = {{"signals_csv", run_dir + "/signals.csv"}};
  if (!plots || cmp.signals.empty()) return;
  std::string why;
  if (plot::write_png(signals_figure(scene, cmp), run_dir + "/signals.png", &why))
    summary["files"]["signals_png"] = run_dir + "/signals.png";
  else
    std::fprintf(stderr, "mechsim: no plot: %s\n", why.c_str());
}

void plot_lateness(const config::Scene& scene, const std::string& run_dir, json& summary) {
  std::string why;
  const auto pngs = write_lateness_plots(summary["realtime"], scene.time.step / scene.rtf, run_dir, &why);
  for (const auto& png : pngs) summary["files"]["lateness_png"].push_back(png);
  if (pngs.empty() && !why.empty()) std::fprintf(stderr, "mechsim: no lateness plot: %s\n", why.c_str());
}

}  // namespace mechsim::launch
