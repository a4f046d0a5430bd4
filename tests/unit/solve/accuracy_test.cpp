// Accuracy of every method against analytic solutions.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/solve/block_integrator.h"
#include "test_blocks.h"

namespace mechsim::solve {
namespace {

class AccuracyEveryMethod : public ::testing::TestWithParam<Method> {};

INSTANTIATE_TEST_SUITE_P(Solve, AccuracyEveryMethod,
                         ::testing::Values(Method::cvode_bdf, Method::cvode_adams,
                                           Method::arkode_erk, Method::arkode_dirk));

TEST_P(AccuracyEveryMethod, ExponentialDecayMatchesExp) {
  const double rate = 2.0;
  test::DecayBlock block(rate);
  SolverOptions options;
  options.method = GetParam();
  options.rtol = 1e-6;
  options.atol = 1e-9;
  const std::vector<double> x0{1.0};
  BlockIntegrator integrator(block, options, 0.0, x0);

  // Each step's local error is held below rtol*|x| + atol. On x' = -a x a relative error
  // is carried forward unchanged, so the global relative error is at most the sum of the
  // local ones; in practice the step controller keeps them well below the tolerance and
  // they partly cancel: SUNDIALS' BDF typically ends 10-30x rtol off at this setting, the
  // others closer. 50x is a ceiling with margin, still 200x below the error of a missed
  // stop time (|x'| h ~ 1e-2) and far below a method losing an order.
  const double allowed_factor = 50.0;
  for (int k = 1; k <= 12; ++k) {
    const double t = 0.25 * k;
    integrator.advance_to(t, {});
    ASSERT_EQ(integrator.time(), t);  // the stop time is hit exactly
    const double exact = std::exp(-rate * t);
    EXPECT_NEAR(integrator.state()[0], exact, allowed_factor * (options.rtol * exact + options.atol))
        << "t = " << t;
  }
  EXPECT_GT(integrator.stats().steps, 0);
  EXPECT_EQ(integrator.stats().restarts, 0);  // no discontinuity was declared
}

// m x'' = -k x + F, F an input held per macro step (zero-order hold, as a co-simulation
// delivers it); F switches from f1 to f2 at t_switch.
class ForcedOscillator final : public models::Block {
 public:
  ForcedOscillator(double mass, double stiffness)
      : Block("test_forced_oscillator"), mass_(mass), stiffness_(stiffness) {
    declare_input("force", "N", 0.0);
    declare_state("x", "m");
    declare_state("v", "m/s");
    declare_output("x", "m");
  }
  void derivatives(double, std::span<const double> x, std::span<const double> u,
                   std::span<double> dxdt) const override {
    dxdt[0] = x[1];
    dxdt[1] = (u[0] - stiffness_ * x[0]) / mass_;
  }
  void calc_outputs(double, std::span<const double> x, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = x[0];
  }

 private:
  double mass_, stiffness_;
};

TEST_P(AccuracyEveryMethod, HarmonicOscillatorWithHeldForceMatchesAnalyticSolution) {
  const double mass = 2.0, stiffness = 50.0;  // omega = 5 rad/s, period 1.26 s
  const double omega = std::sqrt(stiffness / mass);
  const double f1 = 1.0, f2 = -2.0, t_switch = 1.0, x_start = 0.1;
  ForcedOscillator block(mass, stiffness);
  SolverOptions options;
  options.method = GetParam();
  options.rtol = 1e-8;
  options.atol = 1e-10;
  BlockIntegrator integrator(block, options, 0.0, std::vector<double>{x_start, 0.0});

  // Free oscillation about the static deflection F/k, from (x_a, v_a) at t_a.
  auto analytic = [&](double t, double t_a, double x_a, double v_a, double force) {
    const double offset = force / stiffness, tau = t - t_a;
    const double c = std::cos(omega * tau), s = std::sin(omega * tau);
    return std::pair{offset + (x_a - offset) * c + v_a / omega * s,
                     -(x_a - offset) * omega * s + v_a * c};
  };
  const auto [x_switch, v_switch] = analytic(t_switch, 0.0, x_start, 0.0, f1);
  const double amplitude = std::abs(x_start - f1 / stiffness) + std::abs(f2 - f1) / stiffness;

  // The oscillator is not contractive: each step's local error (<= rtol * amplitude) stays
  // as an amplitude or phase error, so the global error is bounded by the number of steps
  // times rtol * amplitude, and each of the 30 restarts adds start-up steps at order 1.
  // BDF, the least accurate here, takes ~1200 steps over the 3 s; their errors partly
  // cancel, so 1e3 * rtol * amplitude (1e-6 m) is a safe ceiling. Missing the force switch
  // by one macro step would be off by ~(3 N / 2 kg) (0.1 s)^2 / 2 = 7.5e-3 m.
  const double tolerance = 1e3 * options.rtol * amplitude;
  const double macro_step = 0.1;
  for (int k = 0; k < 30; ++k) {
    const double t_start = k * macro_step, t_end = (k + 1) * macro_step;
    const double held_force = t_start < t_switch - 1e-12 ? f1 : f2;
    if (k > 0) integrator.mark_discontinuity();
    integrator.advance_to(t_end, [held_force](double, std::span<double> u) { u[0] = held_force; });
    const auto [x_exact, v_exact] = t_end <= t_switch + 1e-12
                                        ? analytic(t_end, 0.0, x_start, 0.0, f1)
                                        : analytic(t_end, t_switch, x_switch, v_switch, f2);
    EXPECT_NEAR(integrator.state()[0], x_exact, tolerance) << "t = " << t_end;
    EXPECT_NEAR(integrator.state()[1], v_exact, omega * tolerance) << "t = " << t_end;
  }
}

}  // namespace
}  // namespace mechsim::solve
