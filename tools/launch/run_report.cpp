#include "run_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "mechsim/config/units.h"

namespace mechsim::launch {

using nlohmann::json;

namespace {

// Time at which y first crosses `level` going from y0's side, linearly interpolated.
double first_crossing(std::span<const double> t, std::span<const double> y, double level, bool rising) {
  for (std::size_t i = 1; i < y.size(); ++i) {
    const bool crossed = rising ? (y[i - 1] < level && y[i] >= level) : (y[i - 1] > level && y[i] <= level);
    if (crossed) return t[i - 1] + (level - y[i - 1]) / (y[i] - y[i - 1]) * (t[i] - t[i - 1]);
  }
  return NAN;
}

// Trapezoidal integral of y over t.
double integral(std::span<const double> t, std::span<const double> y) {
  double sum = 0.0;
  for (std::size_t i = 1; i < y.size() && i < t.size(); ++i) sum += 0.5 * (y[i] + y[i - 1]) * (t[i] - t[i - 1]);
  return sum;
}

// supplied work = dissipated work + change of the stored energies, each term by name.
json energy_balance(const config::ReportSpec& r, std::span<const double> t, const SeriesLookup& series) {
  json f, terms = json::object();
  double sums[3] = {0.0, 0.0, 0.0};
  const std::vector<config::SignalRef>* lists[3] = {&r.supplied, &r.dissipated, &r.stored};
  for (int g = 0; g < 3; ++g)
    for (const auto& s : *lists[g]) {
      auto y = series(s);
      if (y.empty()) return nullptr;
      const double v = g < 2 ? integral(t, y) : y.back() - y.front();
      terms[s.full_name()] = v;
      sums[g] += v;
    }
  const double residual = sums[0] - sums[1] - sums[2];
  f["supplied_J"] = sums[0];
  f["dissipated_J"] = sums[1];
  f["stored_change_J"] = sums[2];
  f["residual_J"] = residual;
  // Normalised by the supplied work (the figure the balance is about).
  f["relative_residual"] = std::abs(residual) / std::max(std::abs(sums[0]), 1e-300);
  f["terms_J"] = terms;
  return f;
}

json figure_of(const config::ReportSpec& r, std::span<const double> t, const SeriesLookup& series) {
  if (r.stat == "energy_balance") return energy_balance(r, t, series);
  auto y = series(r.signal);
  if (y.empty()) return nullptr;
  json f;
  std::size_t at_index = 0;
  if (r.stat == "min" || r.stat == "max" || r.stat == "max_abs") {
    auto it = r.stat == "min" ? std::min_element(y.begin(), y.end())
              : r.stat == "max" ? std::max_element(y.begin(), y.end())
                                : std::max_element(y.begin(), y.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    at_index = static_cast<std::size_t>(it - y.begin());
    f["value"] = r.stat == "max_abs" ? std::abs(*it) : *it;
    f["t_s"] = t[at_index];
  } else if (r.stat == "final") {
    at_index = y.size() - 1;
    f["value"] = y.back();
  } else if (r.stat == "time_true") {
    double on = 0.0;
    for (std::size_t i = 1; i < y.size(); ++i)
      if (y[i - 1] > 0.5) on += t[i] - t[i - 1];
    f["value"] = on;
  } else if (r.stat == "step_response") {
    const double target = r.target.empty() ? y.back() : config::parse_quantity(r.target).value_si;
    StepResponse s = step_response(t, y, target, r.band);
    f["rise_time_s"] = s.rise_time;
    f["overshoot_pct"] = 100 * s.overshoot;
    f["settling_time_s"] = s.settling_time;
    f["final_value"] = s.final_value;
    f["final_error"] = s.final_value - target;
    f["settled"] = s.settled;
    f["target"] = target;
    return f;
  }
  if (r.at) {
    auto at = series(*r.at);
    if (!at.empty()) {
      double v = at[at_index];
      if (r.at_wrap_turn) v = std::fmod(std::fmod(v, 2 * std::numbers::pi) + 2 * std::numbers::pi, 2 * std::numbers::pi);
      f["at"] = {{"signal", r.at->full_name()}, {"value", v / r.at_scale}, {"unit", r.at_unit.empty() ? "SI" : r.at_unit}};
    }
  }
  return f;
}

double relative_difference(double a, double b) {
  const double scale = std::max(std::abs(b), 1e-300);
  return std::abs(a - b) / scale;
}

}  // namespace

StepResponse step_response(std::span<const double> t, std::span<const double> y, double target, double band) {
  StepResponse s;
  if (y.size() < 2) return s;
  const double y0 = y.front(), step = target - y0;
  const bool rising = step > 0;
  s.final_value = y.back();
  s.rise_time = first_crossing(t, y, y0 + 0.9 * step, rising) - first_crossing(t, y, y0 + 0.1 * step, rising);
  const double peak = rising ? *std::max_element(y.begin(), y.end()) : *std::min_element(y.begin(), y.end());
  s.overshoot = std::max(0.0, (peak - target) / step);
  const double tolerance = band * std::abs(step);
  s.settled = std::abs(y.back() - target) <= tolerance;
  // Settling: after the last sample outside the band, interpolated onto the band edge.
  s.settling_time = NAN;
  if (s.settled) {
    std::size_t last_out = 0;
    bool any_out = false;
    for (std::size_t i = 0; i < y.size(); ++i)
      if (std::abs(y[i] - target) > tolerance) {
        last_out = i;
        any_out = true;
      }
    if (!any_out) {
      s.settling_time = 0.0;
    } else {
      const double edge = y[last_out] > target ? target + tolerance : target - tolerance;
      const std::size_t i = last_out + 1;
      s.settling_time = t[i - 1] + (edge - y[i - 1]) / (y[i] - y[i - 1]) * (t[i] - t[i - 1]) - t.front();
    }
  }
  return s;
}

json report_figures(const config::Scene& scene, std::span<const double> t, const SeriesLookup& series,
                    const SeriesLookup* reference) {
  json out = json::array();
  for (const auto& r : scene.report) {
    json f = figure_of(r, t, series);
    if (f.is_null()) continue;
    f["stat"] = r.stat;
    f["signal"] = r.signal.full_name();
    if (reference) {
      json ref = figure_of(r, t, *reference);
      if (!ref.is_null()) {
        json diff = json::object();
        for (const char* key : {"value", "rise_time_s", "settling_time_s", "final_value", "overshoot_pct", "supplied_J",
                                "dissipated_J", "stored_change_J"})
          if (f.contains(key) && ref.contains(key) && f[key].is_number() && ref[key].is_number())
            diff[key] = relative_difference(f[key].get<double>(), ref[key].get<double>());
        ref.erase("stat");
        f["reference"] = ref;
        f["relative_difference"] = diff;
      }
    }
    out.push_back(f);
  }
  return out;
}

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
