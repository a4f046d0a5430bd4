// Slide torsion eigenmodels (spec nc_slide.md §2) and the shaft discretisations behind them.
#include "mechsim/models/nc/slide_torsion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mechsim::models::nc {
namespace {

constexpr double two_pi = 2 * std::numbers::pi;

TEST(SlideDriveDataTest, DerivedQuantitiesMatchSpec) {
  const SlideDriveData d = SlideDriveData::report_cnc200();
  // The spec prints 3 significant digits: half a unit in the last one.
  EXPECT_NEAR(d.spindle_inertia(), 1.73e-3, 0.005e-3);
  EXPECT_NEAR(d.spindle_stiffness(), 7.86e3, 0.005e3);
  EXPECT_NEAR(d.coupling_equivalent_length(), 0.51, 0.005);
  EXPECT_DOUBLE_EQ(d.slide_inertia(), 2.1e-4);
  // Without the override: m s²/4π² with the 5 mm lead.
  const SlideDriveData formula;
  EXPECT_NEAR(formula.slide_inertia(), 235 * 0.005 * 0.005 / (4 * std::numbers::pi * std::numbers::pi), 1e-15);
}

TEST(SlideTorsionTest, ModelOneAt520Hz) {
  // Report: 520 Hz, printed to 3 digits (±0.5 Hz).
  EXPECT_NEAR(two_inertia_frequency_hz(SlideDriveData::report_cnc200()), 520.0, 0.5);
}

TEST(SlideTorsionTest, ModelTwoMatchesKlottersTwoMassFormula) {
  const SlideDriveData d = SlideDriveData::report_cnc200();
  const double i1 = d.coupling_inertia + d.spindle_inertia() / 2, i2 = d.slide_inertia() + d.spindle_inertia() / 2;
  const double c1 = d.coupling_stiffness, c2 = d.spindle_stiffness();
  // Closed form for frame —c1— I1 —c2— I2: ω² = (S ∓ √(S² − 4 c1 c2/(I1 I2)))/2, S = (c1+c2)/I1 + c2/I2.
  const double sum = (c1 + c2) / i1 + c2 / i2;
  const double root = std::sqrt(sum * sum - 4 * c1 * c2 / (i1 * i2));
  const auto f = grounded_chain_frequencies_hz(d);
  // Two exact methods on a 2×2 problem: round-off only.
  EXPECT_NEAR(f.first_hz, std::sqrt((sum - root) / 2) / two_pi, 1e-9 * f.first_hz);
  EXPECT_NEAR(f.second_hz, std::sqrt((sum + root) / 2) / two_pi, 1e-9 * f.second_hz);
}

TEST(SlideTorsionTest, ModelThreeAt786HzAtMidPosition) {
  const SlideDriveData report = SlideDriveData::report_cnc200();
  // Report: 786 Hz with 3 Ritz shapes at mid position; ±2 % is the brief's bound. With the
  // report's I_slide this gives 783.1 Hz (−0.4 %).
  EXPECT_NEAR(continuous_shaft_frequency_hz(report, mid_slide_position(report), 3), 786.0, 0.02 * 786.0);
  // With m s²/4π² (5 mm lead) the report's figure comes out to its printed digits (±0.5 Hz):
  // the report evidently used that inertia in model 3, not its 2.1e-4 kg m².
  const SlideDriveData formula;
  EXPECT_NEAR(continuous_shaft_frequency_hz(formula, mid_slide_position(formula), 3), 786.0, 0.5);
}

TEST(SlideTorsionTest, SlideAtTheEquivalentShaftMiddleSitsInTheNode) {
  const SlideDriveData d = SlideDriveData::report_cnc200();
  const double total = d.coupling_equivalent_length() + d.spindle_length;
  const double node = total / 2 - d.coupling_equivalent_length();
  // cos(πs/L) is an exact free–free mode with the slide in its node and lies in every Ritz
  // space with N >= 2, so Ritz returns it exactly: f = √(G/ρ)/(2L), any slide inertia.
  const double exact = std::sqrt(d.shear_modulus / d.density) / (2 * total);
  for (int n : {2, 3, 8}) EXPECT_NEAR(continuous_shaft_frequency_hz(d, node, n), exact, 1e-9 * exact);
  SlideDriveData heavy = d;
  heavy.slide_inertia_override = 1e-2;
  EXPECT_NEAR(continuous_shaft_frequency_hz(heavy, node, 3), exact, 1e-9 * exact);
}

TEST(SlideTorsionTest, FrequencyAgainstPositionPeaksAtTheNode) {
  const SlideDriveData d = SlideDriveData::report_cnc200();
  std::vector<double> positions;
  const double step = 0.01;
  for (int i = 0; i <= 150; ++i) positions.push_back(i * step);  // 0 .. l = 1.5 m
  const auto sweep = frequency_vs_slide_position(d, positions);
  auto best = sweep.begin();
  for (auto it = sweep.begin(); it != sweep.end(); ++it)
    if (it->frequency_hz > best->frequency_hz) best = it;
  const double node = (d.spindle_length - d.coupling_equivalent_length()) / 2;
  // The maximum lies "near the middle", at the node; the grid resolves it to one step.
  EXPECT_NEAR(best->slide_position, node, step);
  // Elsewhere the slide inertia takes part and lowers f0.
  EXPECT_LT(sweep.front().frequency_hz, best->frequency_hz);
  EXPECT_LT(sweep.back().frequency_hz, best->frequency_hz);
}

TEST(SlideTorsionTest, RitzFallsAndFeChainRisesTowardsTheSameLimit) {
  const SlideDriveData d = SlideDriveData::report_cnc200();
  const double x = mid_slide_position(d);
  // Ritz on nested spaces: upper bounds that cannot increase (1e-12 relative for round-off).
  double previous_ritz = continuous_shaft_frequency_hz(d, x, 2);
  for (int n : {3, 5, 10, 20, 40}) {
    const double f = continuous_shaft_frequency_hz(d, x, n);
    EXPECT_LE(f, previous_ritz * (1 + 1e-12)) << n;
    previous_ritz = f;
  }
  // Lumped-mass FE of a uniform shaft converges from below, O(h²).
  double previous_fe = continuous_shaft_fe_frequency_hz(d, x, 10);
  std::vector<double> fe{previous_fe};
  for (int n : {20, 40, 80, 160, 320, 640}) {
    const double f = continuous_shaft_fe_frequency_hz(d, x, n);
    EXPECT_GT(f, previous_fe) << n;
    EXPECT_LT(f, previous_ritz) << n;  // below every Ritz bound
    fe.push_back(f);
    previous_fe = f;
  }
  // O(h²): successive differences shrink by about 4 when h halves (3..5 allows for the
  // mesh being re-split around the slide).
  const std::size_t k = fe.size() - 1;
  const double ratio = (fe[k - 1] - fe[k - 2]) / (fe[k] - fe[k - 1]);
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 5.0);
  // Both refined: they meet. Ritz converges slowly (the slide's kink in the mode shape),
  // about 1/N: at N = 40 within 1e-4 of the converged FE value.
  EXPECT_NEAR(previous_ritz, previous_fe, 1e-4 * previous_fe);
  // The report's 3 shapes are already within 0.1 % of the limit.
  EXPECT_NEAR(continuous_shaft_frequency_hz(d, x, 3), previous_fe, 1e-3 * previous_fe);
}

TEST(SlideTorsionTest, FeChainOfABareShaftMatchesItsAnalyticModes) {
  // No lumps: f_n = n √(G/ρ)/(2L). Lumped-mass FE error is −(nπh/L)²/24 relative.
  const UniformShaft shaft{2.0, 8e10 * 1.5e-7, 7850 * 1.5e-7};
  const int elements = 400;
  const Eigen::VectorXd f = fe_chain_frequencies_hz(shaft, {}, elements);
  const double wave_speed = std::sqrt(8e10 / 7850.0);
  for (int n = 1; n <= 3; ++n) {
    const double exact = n * wave_speed / (2 * shaft.length);
    const double h_ratio = n * std::numbers::pi / elements;
    EXPECT_NEAR(f(n), exact * (1 - h_ratio * h_ratio / 24), 1e-3 * exact * h_ratio * h_ratio) << n;
  }
  // The rigid mode: its ω² is round-off against ω1² (1e-16 times the matrix condition).
  EXPECT_LT(f(0) * f(0), 1e-9 * f(1) * f(1));
  // Ritz with cosines is exact for the bare shaft.
  const Eigen::VectorXd r = ritz_frequencies_hz(shaft, {}, 4);
  for (int n = 1; n <= 3; ++n) EXPECT_NEAR(r(n), n * wave_speed / (2 * shaft.length), 1e-9 * r(n));
}

TEST(SlideTorsionTest, DiameterSweepMatchesSinglePointModels) {
  const SlideDriveData d = SlideDriveData::report_cnc200();
  std::vector<double> diameters;
  for (int mm = 31; mm <= 39; ++mm) diameters.push_back(mm * 1e-3);
  const auto sweep = frequencies_vs_diameter(d, diameters, mid_slide_position(d));
  ASSERT_EQ(sweep.size(), diameters.size());
  // d = 35 mm is the nominal case itself, to the last bits (the same uniform shaft).
  EXPECT_EQ(sweep[4].model1_hz, two_inertia_frequency_hz(d));
  EXPECT_EQ(sweep[4].model3_hz, continuous_shaft_frequency_hz(d, mid_slide_position(d)));
  for (std::size_t i = 1; i < sweep.size(); ++i) {
    // Only the spindle changes (spec §2: the coupling stays its 0.51 m piece of 35 mm
    // spindle). In model 3 the spindle part's stiffness and inertia both grow as d⁴ while
    // the coupling piece and the slide inertia stay: the mode, whose twist sits mostly in the
    // spindle with the slide at mid position, stiffens more than it gains inertia, so f0
    // rises with d (the report's trend). Model 1 is not monotonic (its series spring
    // saturates at C_kopp while I_sp/2 grows): it is not asserted.
    EXPECT_GT(sweep[i].model3_hz, sweep[i - 1].model3_hz) << sweep[i].diameter;
    EXPECT_LT(sweep[i].model2_first_hz, sweep[i].model2_second_hz);
  }
}

TEST(SlideTorsionTest, TheCouplingKeepsItsPieceOf35MmSpindleWhateverTheSpindle) {
  // l_eq = G J(35 mm) / C_kopp = 8e10 * 1.4732e-7 / 23e3 = 0.5124 m (spec: "≈ 0.51 m"), at
  // every swept diameter; the equivalent shaft is stepped there: piece, then spindle.
  const SlideDriveData d = SlideDriveData::report_cnc200();
  const double l_eq = d.shear_modulus * std::numbers::pi * std::pow(0.035, 4) / 32 / d.coupling_stiffness;
  EXPECT_NEAR(l_eq, 0.51, 0.005);
  for (double mm : {31.0, 35.0, 39.0}) {
    const SlideDriveData varied = with_spindle_diameter(d, mm * 1e-3);
    EXPECT_NEAR(varied.coupling_equivalent_length(), l_eq, 1e-15) << mm;
    const SteppedShaft shaft = equivalent_shaft(varied);
    EXPECT_EQ(shaft.segments.size(), mm == 35.0 ? 1u : 2u) << mm;
    EXPECT_NEAR(shaft.length(), l_eq + d.spindle_length, 1e-12) << mm;
  }
}

TEST(SlideTorsionTest, SteppedBareShaftMatchesItsFrequencyEquation) {
  // Free-free shaft of two segments of one material (wave speed c): the modes satisfy
  // GJ1 tan(k l1) + GJ2 tan(k l2) = 0, k = ω/c. The 0.51 m piece of 35 mm spindle and a
  // 1.5 m spindle of 39 mm: the lowest root by bisection against the FE chain (O(h²): 2048
  // elements put it within ~1e-6) and against Ritz with 40 cosines (an upper bound that
  // converges slowly at the kink of the step: 1 %).
  const double G = 8e10, rho = 7850, c = std::sqrt(G / rho);
  auto polar = [](double dia) { return std::numbers::pi * std::pow(dia, 4) / 32; };
  const double l1 = 0.5124, l2 = 1.5, gj1 = G * polar(0.035), gj2 = G * polar(0.039);
  const SteppedShaft shaft({{l1, gj1, rho * polar(0.035)}, {l2, gj2, rho * polar(0.039)}});
  auto g = [&](double k) { return gj1 * std::sin(k * l1) * std::cos(k * l2) + gj2 * std::sin(k * l2) * std::cos(k * l1); };
  // g > 0 just above k = 0; the first root lies below π/(l1 + l2) times 2 (the uniform shaft's
  // first mode is π/L, a step moves it by far less than a factor 2).
  double lo = 1e-6, hi = 2 * std::numbers::pi / (l1 + l2);
  ASSERT_GT(g(lo), 0);
  double k = lo;
  for (double step = (hi - lo) / 1000, x = lo; x < hi; x += step)
    if (g(x) * g(x + step) <= 0) {
      double a = x, b = x + step;
      for (int i = 0; i < 200; ++i) {
        const double m = (a + b) / 2;
        (g(a) * g(m) <= 0 ? b : a) = m;
      }
      k = (a + b) / 2;
      break;
    }
  const double exact_hz = k * c / (2 * std::numbers::pi);
  EXPECT_NEAR(fe_chain_frequencies_hz(shaft, {}, 2048)(1), exact_hz, 1e-5 * exact_hz);
  const double ritz = ritz_frequencies_hz(shaft, {}, 40)(1);
  EXPECT_GE(ritz, exact_hz * (1 - 1e-9));  // Ritz: an upper bound
  EXPECT_NEAR(ritz, exact_hz, 0.01 * exact_hz);
}

TEST(SlideTorsionTest, RejectsPositionsOffTheSpindle) {
  const SlideDriveData d;
  EXPECT_THROW(continuous_shaft_frequency_hz(d, -0.1), std::invalid_argument);
  EXPECT_THROW(continuous_shaft_frequency_hz(d, d.spindle_length + 0.1), std::invalid_argument);
  EXPECT_THROW(continuous_shaft_frequency_hz(d, 0.5, 1), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::models::nc
