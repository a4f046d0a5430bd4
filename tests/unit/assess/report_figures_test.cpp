// The report's figures (libs/assess report_figures.h) on analytic signals: a first- and a
// second-order step response, an extremum with a signal at it, time in a state, an energy
// balance, and the differences to a reference.
#include "mechsim/assess/report_figures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

namespace mechsim::assess {
namespace {

constexpr double kDt = 1e-4;

std::vector<double> grid(double end) {
  std::vector<double> t;
  for (int k = 0; k * kDt <= end + 1e-12; ++k) t.push_back(k * kDt);
  return t;
}

template <class F>
std::vector<double> sample(const std::vector<double>& t, F f) {
  std::vector<double> y(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) y[k] = f(t[k]);
  return y;
}

TEST(StepResponse, FirstOrderLagHasItsAnalyticRiseAndSettlingTimes) {
  // y = 1 - exp(-t/tau): 10 % at tau ln(10/9), 90 % at tau ln 10, so the rise takes tau ln 9;
  // within 2 % of the step from tau ln 50 on; no overshoot. The crossings are interpolated
  // linearly between samples: the error is at most y'' dt^2 / 8 / y' = dt^2 / (8 tau), 1e-9 s.
  const double tau = 0.1;
  const auto t = grid(1.0);
  const auto y = sample(t, [&](double s) { return 1 - std::exp(-s / tau); });
  const StepResponse s = step_response(t, y, 1.0, 0.02);
  EXPECT_NEAR(s.rise_time, tau * std::log(9.0), 1e-8);
  EXPECT_NEAR(s.settling_time, tau * std::log(50.0), 1e-8);
  EXPECT_EQ(s.overshoot, 0.0);
  EXPECT_TRUE(s.settled);
  EXPECT_NEAR(s.final_value, 1 - std::exp(-10.0), 1e-15);
}

TEST(StepResponse, UnderdampedSecondOrderOvershootsByTheAnalyticFraction) {
  // y = 1 - exp(-zeta w t) (cos(wd t) + zeta / sqrt(1 - zeta^2) sin(wd t)) peaks at t = pi/wd
  // at 1 + exp(-zeta pi / sqrt(1 - zeta^2)). The largest sample lies within dt/2 of the peak,
  // where y' = 0: it is low by at most y'' dt^2 / 8 ~ w^2 dt^2 / 8 = 5e-5 (w = 2 pi 10 / s).
  const double zeta = 0.3, w = 2 * M_PI * 10, wd = w * std::sqrt(1 - zeta * zeta);
  const auto t = grid(2.0);
  const auto y = sample(t, [&](double s) {
    return 1 - std::exp(-zeta * w * s) * (std::cos(wd * s) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * s));
  });
  const StepResponse s = step_response(t, y, 1.0, 0.02);
  EXPECT_NEAR(s.overshoot, std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)), 5e-5);
  EXPECT_TRUE(s.settled);
  // The envelope exp(-zeta w t) sqrt(1 + zeta^2/(1-zeta^2)) falls under 2 % at about 0.22 s;
  // the oscillation leaves the band for the last time before that.
  EXPECT_GT(s.settling_time, 0.1);
  EXPECT_LT(s.settling_time, 0.23);
}

TEST(StepResponse, NotReachingTheBandIsNotSettled) {
  const auto t = grid(0.1);
  const auto y = sample(t, [](double s) { return s; });  // reaches 0.1 of a step to 1
  const StepResponse s = step_response(t, y, 1.0, 0.02);
  EXPECT_FALSE(s.settled);
  EXPECT_TRUE(std::isnan(s.settling_time));
}

config::SignalRef ref(const std::string& participant, const std::string& output) { return {participant, output, ""}; }

config::ReportSpec spec(const std::string& stat, const config::SignalRef& signal) {
  config::ReportSpec r;
  r.stat = stat;
  r.signal = signal;
  return r;
}

TEST(ReportFigures, ExtremaTimeTrueAndEnergyBalanceWithTheReference) {
  const auto t = grid(1.0);
  // The run: y = sin(2 pi t) peaks at t = 0.25 s; flag > 0.5 for t in [0.2, 0.7) (0.5 s);
  // supplied power 2 W and dissipated 1.5 W over 1 s, the stored energy rising by 0.5 J.
  std::map<std::string, std::vector<double>> run{
      {"a.y", sample(t, [](double s) { return std::sin(2 * M_PI * s); })},
      {"a.angle", sample(t, [](double s) { return 4 * M_PI * s; })},
      {"a.flag", sample(t, [](double s) { return s >= 0.2 - 1e-12 && s < 0.7 - 1e-12 ? 1.0 : 0.0; })},
      {"a.p_in", sample(t, [](double) { return 2.0; })},
      {"a.p_loss", sample(t, [](double) { return 1.5; })},
      {"a.stored", sample(t, [](double s) { return 0.5 * s; })}};
  // The reference: the same with y 1 % larger.
  auto reference_signals = run;
  for (double& v : reference_signals["a.y"]) v *= 1.01;
  auto lookup = [](std::map<std::string, std::vector<double>>& m) {
    return [&m](const config::SignalRef& r) -> std::span<const double> {
      auto it = m.find(r.full_name());
      return it == m.end() ? std::span<const double>{} : std::span<const double>(it->second);
    };
  };
  config::Scene scene;
  config::ReportSpec max = spec("max", ref("a", "y"));
  max.at = ref("a", "angle");
  max.at_unit = "deg";
  max.at_scale = M_PI / 180;
  max.at_wrap_turn = true;
  config::ReportSpec on = spec("time_true", ref("a", "flag"));
  config::ReportSpec energy = spec("energy_balance", ref("a", "p_in"));
  energy.supplied = {ref("a", "p_in")};
  energy.dissipated = {ref("a", "p_loss")};
  energy.stored = {ref("a", "stored")};
  config::ReportSpec unknown = spec("final", ref("b", "missing"));
  scene.report = {max, on, energy, unknown};
  const SeriesLookup reference = lookup(reference_signals);
  const auto figures = report_figures(scene, t, lookup(run), &reference);
  ASSERT_EQ(figures.size(), 3u);  // the entry on an unknown signal is left out

  const ReportFigure& f = figures[0];
  EXPECT_EQ(f.stat, "max");
  EXPECT_EQ(f.signal, "a.y");
  EXPECT_DOUBLE_EQ(*f.run.value, 1.0);  // the sample at t = 0.25 s hits the peak
  EXPECT_NEAR(*f.run.t, 0.25, 1e-12);
  // The angle 4 pi t at 0.25 s is pi: 180 deg after wrapping into one turn.
  ASSERT_TRUE(f.run.at);
  EXPECT_NEAR(f.run.at->value, 180.0, 1e-9);
  EXPECT_EQ(f.run.at->unit, "deg");
  ASSERT_TRUE(f.reference && f.difference);
  EXPECT_NEAR(*f.reference->value, 1.01, 1e-12);
  EXPECT_NEAR(*f.difference->value, 0.01 / 1.01, 1e-12);
  EXPECT_FALSE(f.difference->rise_time);  // not a step response

  // Flag on from 0.2 s to 0.7 s: the time counts the intervals that start on, 0.5 s to a sample.
  EXPECT_NEAR(*figures[1].run.value, 0.5, kDt + 1e-12);
  EXPECT_EQ(*figures[1].difference->value, 0.0);

  // Constant powers integrate exactly by trapezoids: 2 J and 1.5 J; stored 0.5 J; no residual
  // beyond rounding of a thousand-term sum.
  const EnergyBalance& e = *figures[2].run.energy;
  EXPECT_NEAR(e.supplied, 2.0, 1e-12);
  EXPECT_NEAR(e.dissipated, 1.5, 1e-12);
  EXPECT_NEAR(e.stored_change, 0.5, 1e-12);
  EXPECT_NEAR(e.relative_residual, 0.0, 1e-11);
  EXPECT_EQ(e.terms.size(), 3u);
  EXPECT_EQ(*figures[2].difference->supplied, 0.0);
}

TEST(ReportFigures, WithoutAReferenceNoDifferences) {
  const auto t = grid(0.5);
  auto y = sample(t, [](double s) { return 1 - std::exp(-s / 0.05); });
  config::Scene scene;
  config::ReportSpec step = spec("step_response", ref("a", "y"));
  step.target = "1";
  scene.report = {step};
  const auto figures = report_figures(scene, t, [&](const config::SignalRef&) { return std::span<const double>(y); });
  ASSERT_EQ(figures.size(), 1u);
  ASSERT_TRUE(figures[0].run.step);
  EXPECT_EQ(figures[0].run.step->target, 1.0);
  EXPECT_DOUBLE_EQ(figures[0].run.step->final_error, y.back() - 1.0);
  EXPECT_NEAR(figures[0].run.step->response.rise_time, 0.05 * std::log(9.0), 1e-7);
  EXPECT_FALSE(figures[0].reference);
  EXPECT_FALSE(figures[0].difference);
}

}  // namespace
}  // namespace mechsim::assess
