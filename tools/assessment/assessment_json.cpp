#include "assessment_json.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace mechsim::tools {

using nlohmann::json;

namespace {

json figure_values_json(const assess::FigureValues& v) {
  json f;
  if (v.value) f["value"] = *v.value;
  if (v.t) f["t_s"] = *v.t;
  if (v.at) f["at"] = {{"signal", v.at->signal}, {"value", v.at->value}, {"unit", v.at->unit}};
  if (v.step) {
    const assess::StepResponse& s = v.step->response;
    f["rise_time_s"] = s.rise_time;
    f["overshoot_pct"] = 100 * s.overshoot;
    f["settling_time_s"] = s.settling_time;
    f["final_value"] = s.final_value;
    f["final_error"] = v.step->final_error;
    f["settled"] = s.settled;
    f["target"] = v.step->target;
  }
  if (v.energy) {
    const assess::EnergyBalance& e = *v.energy;
    json terms = json::object();
    for (const auto& [name, value] : e.terms) terms[name] = value;
    f["supplied_J"] = e.supplied;
    f["dissipated_J"] = e.dissipated;
    f["stored_change_J"] = e.stored_change;
    f["residual_J"] = e.residual;
    f["relative_residual"] = e.relative_residual;
    f["terms_J"] = terms;
  }
  return f;
}

json differences_json(const assess::FigureDifferences& d) {
  json out = json::object();
  const std::pair<const char*, const std::optional<double>*> keys[] = {
      {"value", &d.value},           {"rise_time_s", &d.rise_time}, {"settling_time_s", &d.settling_time},
      {"final_value", &d.final_value}, {"overshoot_pct", &d.overshoot}, {"supplied_J", &d.supplied},
      {"dissipated_J", &d.dissipated}, {"stored_change_J", &d.stored_change}};
  for (const auto& [key, value] : keys)
    if (*value) out[key] = **value;
  return out;
}

}  // namespace

json reference_accuracy_json(const cosim::ReferenceAccuracy& accuracy, std::span<const assess::SignalAccuracy> signals) {
  json by_name = json::object();
  for (const auto& s : signals)
    by_name[s.signal] = {{"max_abs_difference", s.max_abs},
                         {"rms_abs_difference", s.rms_abs},
                         {"max_rel_difference", s.max_rel},
                         {"rms_rel_difference", s.rms_rel}};
  return {{"method", "difference to a re-run at a 100x tighter tolerance"},
          {"rtol_check", accuracy.rtol},
          {"atol_check", accuracy.atol},
          {"wall_time_s", accuracy.wall_time_s},
          {"solver_steps", accuracy.stats.steps},
          {"signals", by_name}};
}

json reference_accuracy_json(const config::Scene& scene, const cosim::ReferenceRun& ref, const cosim::ReferenceAccuracy& accuracy) {
  return reference_accuracy_json(accuracy, assess::reference_signal_accuracy(scene, ref, accuracy));
}

void print_reference_accuracy(const json& accuracy) {
  std::printf("  reference error estimate (against rtol %g):\n", accuracy["rtol_check"].get<double>());
  for (auto& [name, e] : accuracy["signals"].items())
    std::printf("    %-32s max %.3g (%.3g %% of range), rms %.3g\n", name.c_str(), e["max_abs_difference"].get<double>(),
                100 * e["max_rel_difference"].get<double>(), e["rms_abs_difference"].get<double>());
}

json report_figures_json(std::span<const assess::ReportFigure> figures) {
  json out = json::array();
  for (const auto& figure : figures) {
    json f = figure_values_json(figure.run);
    f["stat"] = figure.stat;
    f["signal"] = figure.signal;
    if (figure.reference) {
      f["reference"] = figure_values_json(*figure.reference);
      f["relative_difference"] = differences_json(figure.difference ? *figure.difference : assess::FigureDifferences{});
    }
    out.push_back(f);
  }
  return out;
}

void print_figures(const json& figures) {
  auto number = [](const json& j, const char* key) { return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN; };
  for (const auto& f : figures) {
    const std::string stat = f["stat"], signal = f["signal"];
    if (stat == "energy_balance") {
      std::printf("  energy balance: supplied %.6g J = dissipated %.6g J + stored change %.6g J, residual %.3g J (%.3g %%)",
                  number(f, "supplied_J"), number(f, "dissipated_J"), number(f, "stored_change_J"), number(f, "residual_J"),
                  100 * number(f, "relative_residual"));
      if (f.contains("reference"))
        std::printf("  (reference: residual %.3g %%)", 100 * number(f["reference"], "relative_residual"));
    } else if (stat == "step_response") {
      std::printf("  step response of %s: rise %.4g s, overshoot %.3g %%, settling %.4g s, final error %.3g",
                  signal.c_str(), number(f, "rise_time_s"), number(f, "overshoot_pct"), number(f, "settling_time_s"),
                  number(f, "final_error"));
      if (f.contains("reference"))
        std::printf("  (reference: rise %.4g s, overshoot %.3g %%, settling %.4g s)", number(f["reference"], "rise_time_s"),
                    number(f["reference"], "overshoot_pct"), number(f["reference"], "settling_time_s"));
    } else {
      std::printf("  %s %s = %.6g", stat.c_str(), signal.c_str(), number(f, "value"));
      if (f.contains("t_s")) std::printf(" at t = %.6g s", number(f, "t_s"));
      if (f.contains("at"))
        std::printf(", %s = %.6g %s", f["at"]["signal"].get<std::string>().c_str(), number(f["at"], "value"),
                    f["at"]["unit"].get<std::string>().c_str());
      if (f.contains("reference")) std::printf("  (reference %.6g)", number(f["reference"], "value"));
    }
    std::printf("\n");
  }
}

}  // namespace mechsim::tools
