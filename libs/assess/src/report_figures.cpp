#include "mechsim/assess/report_figures.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mechsim/config/units.h"

namespace mechsim::assess {

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

// nullopt when a term's signal is unknown.
std::optional<EnergyBalance> energy_balance(const config::ReportSpec& r, std::span<const double> t, const SeriesLookup& series) {
  EnergyBalance b;
  double sums[3] = {0.0, 0.0, 0.0};
  const std::vector<config::SignalRef>* lists[3] = {&r.supplied, &r.dissipated, &r.stored};
  for (int g = 0; g < 3; ++g)
    for (const auto& s : *lists[g]) {
      auto y = series(s);
      if (y.empty()) return std::nullopt;
      const double v = g < 2 ? integral(t, y) : y.back() - y.front();
      b.terms[s.full_name()] = v;
      sums[g] += v;
    }
  b.supplied = sums[0];
  b.dissipated = sums[1];
  b.stored_change = sums[2];
  b.residual = sums[0] - sums[1] - sums[2];
  // Normalised by the supplied work (the figure the balance is about).
  b.relative_residual = std::abs(b.residual) / std::max(std::abs(sums[0]), 1e-300);
  return b;
}

// nullopt when the run lacks the entry's signal.
std::optional<FigureValues> figure_of(const config::ReportSpec& r, std::span<const double> t, const SeriesLookup& series) {
  FigureValues f;
  if (r.stat == "energy_balance") {
    f.energy = energy_balance(r, t, series);
    if (!f.energy) return std::nullopt;
    return f;
  }
  auto y = series(r.signal);
  if (y.empty()) return std::nullopt;
  std::size_t at_index = 0;
  if (r.stat == "min" || r.stat == "max" || r.stat == "max_abs") {
    auto it = r.stat == "min" ? std::min_element(y.begin(), y.end())
              : r.stat == "max" ? std::max_element(y.begin(), y.end())
                                : std::max_element(y.begin(), y.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    at_index = static_cast<std::size_t>(it - y.begin());
    f.value = r.stat == "max_abs" ? std::abs(*it) : *it;
    f.t = t[at_index];
  } else if (r.stat == "final") {
    at_index = y.size() - 1;
    f.value = y.back();
  } else if (r.stat == "time_true") {
    double on = 0.0;
    for (std::size_t i = 1; i < y.size(); ++i)
      if (y[i - 1] > 0.5) on += t[i] - t[i - 1];
    f.value = on;
  } else if (r.stat == "step_response") {
    const double target = r.target.empty() ? y.back() : config::parse_quantity(r.target).value_si;
    const StepResponse s = step_response(t, y, target, r.band);
    f.step = StepFigure{s, target, s.final_value - target};
    return f;
  }
  if (r.at) {
    auto at = series(*r.at);
    if (!at.empty()) {
      double v = at[at_index];
      if (r.at_wrap_turn) v = std::fmod(std::fmod(v, 2 * std::numbers::pi) + 2 * std::numbers::pi, 2 * std::numbers::pi);
      f.at = ValueAt{r.at->full_name(), v / r.at_scale, r.at_unit.empty() ? "SI" : r.at_unit};
    }
  }
  return f;
}

double relative_difference(double a, double b) {
  const double scale = std::max(std::abs(b), 1e-300);
  return std::abs(a - b) / scale;
}

// The differences of the figures both runs have (overshoot: of the percentages).
FigureDifferences differences(const FigureValues& run, const FigureValues& ref) {
  FigureDifferences d;
  auto both = [](const std::optional<double>& a, const std::optional<double>& b, std::optional<double>& out) {
    if (a && b) out = relative_difference(*a, *b);
  };
  both(run.value, ref.value, d.value);
  if (run.step && ref.step) {
    const StepResponse &a = run.step->response, &b = ref.step->response;
    d.rise_time = relative_difference(a.rise_time, b.rise_time);
    d.settling_time = relative_difference(a.settling_time, b.settling_time);
    d.final_value = relative_difference(a.final_value, b.final_value);
    d.overshoot = relative_difference(100 * a.overshoot, 100 * b.overshoot);
  }
  if (run.energy && ref.energy) {
    d.supplied = relative_difference(run.energy->supplied, ref.energy->supplied);
    d.dissipated = relative_difference(run.energy->dissipated, ref.energy->dissipated);
    d.stored_change = relative_difference(run.energy->stored_change, ref.energy->stored_change);
  }
  return d;
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

std::vector<ReportFigure> report_figures(const config::Scene& scene, std::span<const double> t, const SeriesLookup& series,
                                         const SeriesLookup* reference) {
  std::vector<ReportFigure> out;
  for (const auto& r : scene.report) {
    std::optional<FigureValues> f = figure_of(r, t, series);
    if (!f) continue;
    ReportFigure figure{r.stat, r.signal.full_name(), std::move(*f), std::nullopt, std::nullopt};
    if (reference) {
      figure.reference = figure_of(r, t, *reference);
      if (figure.reference) figure.difference = differences(figure.run, *figure.reference);
    }
    out.push_back(std::move(figure));
  }
  return out;
}

}  // namespace mechsim::assess
