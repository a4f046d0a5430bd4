// Restarts keep the statistics cumulative; failures and misuse are reported clearly.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/solve/block_integrator.h"
#include "test_blocks.h"

namespace mechsim::solve {
namespace {

class RestartEveryMethod : public ::testing::TestWithParam<Method> {};

INSTANTIATE_TEST_SUITE_P(Solve, RestartEveryMethod,
                         ::testing::Values(Method::cvode_bdf, Method::cvode_adams,
                                           Method::arkode_erk, Method::arkode_dirk));

TEST_P(RestartEveryMethod, StatsAccumulateAcrossRestarts) {
  const double rate = 2.0;
  test::DecayBlock restarted_block(rate), smooth_block(rate);
  SolverOptions options;
  options.method = GetParam();
  BlockIntegrator restarted(restarted_block, options, 0.0, std::vector<double>{1.0});
  BlockIntegrator smooth(smooth_block, options, 0.0, std::vector<double>{1.0});

  SolverStats previous;
  for (int k = 1; k <= 10; ++k) {
    if (k > 1) restarted.mark_discontinuity();
    restarted.advance_to(0.1 * k, {});
    smooth.advance_to(0.1 * k, {});
    const SolverStats& now = restarted.stats();
    // Each macro step takes at least one step and rhs evaluation; counters that went
    // back to zero at the ReInit would make these fail.
    EXPECT_GT(now.steps, previous.steps) << "macro step " << k;
    EXPECT_GT(now.rhs_evals, previous.rhs_evals) << "macro step " << k;
    EXPECT_GE(now.error_test_failures, previous.error_test_failures);
    EXPECT_GE(now.nonlinear_failures, previous.nonlinear_failures);
    EXPECT_GE(now.jacobian_evals, previous.jacobian_evals);
    previous = now;
  }
  EXPECT_EQ(restarted.stats().restarts, 9);
  EXPECT_EQ(smooth.stats().restarts, 0);
  // A restart drops the step size history (and for CVODE the order): it costs steps.
  EXPECT_GT(restarted.stats().steps, smooth.stats().steps);
  EXPECT_GT(restarted.stats().last_step, 0.0);
  EXPECT_GT(restarted.stats().last_order, 0);
  // A restart begins again at order 1 with a fresh step estimate, spending about a local
  // tolerance per start-up step: the error grows with the number of restarts. BDF loses
  // ~4 rtol per macro step here (the others less); 10 rtol per macro step, i.e. 100x for
  // these 10, keeps margin and stays far below a wrong restart state (~1e-2).
  const double exact = std::exp(-rate * 1.0);
  EXPECT_NEAR(restarted.state()[0], exact, 100 * (options.rtol * exact + options.atol));
}

TEST(Restart, ResetStateContinuesFromTheNewState) {
  const double rate = 2.0;
  test::DecayBlock block(rate);
  BlockIntegrator integrator(block, SolverOptions{}, 0.0, std::vector<double>{1.0});
  integrator.advance_to(0.5, {});
  integrator.reset_state(0.5, std::vector<double>{3.0});
  EXPECT_EQ(integrator.state()[0], 3.0);
  integrator.advance_to(1.0, {});
  EXPECT_EQ(integrator.stats().restarts, 1);
  // Decay test tolerance argument again (50x), for x = 3 e^{-a (t - 0.5)}.
  const double exact = 3.0 * std::exp(-rate * 0.5);
  EXPECT_NEAR(integrator.state()[0], exact, 50 * (1e-6 * exact + 1e-9));
}

TEST_P(RestartEveryMethod, SolverFailureNamesTheFlagAndTheBlock) {
  test::DecayBlock block(2.0);
  SolverOptions options;
  options.method = GetParam();
  options.max_steps_per_call = 3;  // far too few for 100 time constants
  BlockIntegrator integrator(block, options, 0.0, std::vector<double>{1.0});
  try {
    integrator.advance_to(50.0, {});
    FAIL() << "expected a solver failure";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("TOO_MUCH_WORK"), std::string::npos) << message;
    EXPECT_NE(message.find("test_decay"), std::string::npos) << message;
  }
}

class ThrowingBlock final : public models::Block {
 public:
  ThrowingBlock() : Block("test_throwing") { declare_state("x", "1"); }
  void derivatives(double t, std::span<const double>, std::span<const double>,
                   std::span<double> dxdt) const override {
    if (t > 0.5) throw std::domain_error("left the model's validity range");
    dxdt[0] = 1.0;
  }
  void calc_outputs(double, std::span<const double>, std::span<const double>,
                    std::span<double>) const override {}
};

TEST(Errors, ExceptionInTheBlockBecomesASolverError) {
  ThrowingBlock block;
  BlockIntegrator integrator(block, SolverOptions{}, 0.0, std::vector<double>{0.0});
  try {
    integrator.advance_to(1.0, {});
    FAIL() << "expected the block's exception to surface";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("RHSFUNC"), std::string::npos) << message;
    EXPECT_NE(message.find("test_throwing"), std::string::npos) << message;
    EXPECT_NE(message.find("left the model's validity range"), std::string::npos) << message;
  }
}

// A block without states has no solver to locate its events: the integrator bisects on time
// (stateless_events.h). g = t - 0.3 s, rising once; the crossing is handled at its far side,
// within the time resolution (1e-10 s), however the advance is cut (here in steps of 0.1 s,
// one ending on the crossing itself, and 0.07 s).
class StatelessWithEvent final : public models::Block {
 public:
  StatelessWithEvent() : Block("test_stateless_with_event") {}
  void calc_outputs(double, std::span<const double>, std::span<const double>,
                    std::span<double>) const override {}
  int num_event_functions() const override { return 1; }
  void event_functions(double t, std::span<const double>, std::span<const double>, std::span<double> g) const override {
    g[0] = t - 0.3;
  }
  bool handle_events(double t, std::span<double>, std::span<const double>, std::span<const int> crossed) override {
    handled.push_back({t, crossed[0]});
    return false;
  }
  std::vector<std::pair<double, int>> handled;
};

TEST(StatelessEvents, ACrossingIsFoundByBisectionAndHandledOnce) {
  for (const double step : {0.1, 0.07}) {
    StatelessWithEvent block;
    BlockIntegrator integrator(block, SolverOptions{}, 0.0, std::vector<double>{});
    for (double t = step; t < 1.0 + step / 2; t += step) integrator.advance_to(std::min(t, 1.0), {});
    ASSERT_EQ(block.handled.size(), 1u) << "step " << step;
    EXPECT_GE(block.handled[0].first, 0.3 - 1e-10) << "step " << step;
    EXPECT_LE(block.handled[0].first, 0.3 + 1e-10) << "step " << step;
    EXPECT_EQ(block.handled[0].second, 1);
    EXPECT_EQ(integrator.take_events().size(), 1u);
  }
}

TEST(Errors, MisuseIsRefused) {
  test::DecayBlock block(1.0);
  EXPECT_THROW(BlockIntegrator(block, SolverOptions{}, 0.0, std::vector<double>{}),
               std::invalid_argument);
  SolverOptions no_tolerance;
  no_tolerance.rtol = 0.0;
  EXPECT_THROW(BlockIntegrator(block, no_tolerance, 0.0, std::vector<double>{1.0}),
               std::invalid_argument);
  BlockIntegrator integrator(block, SolverOptions{}, 1.0, std::vector<double>{1.0});
  EXPECT_THROW(integrator.advance_to(0.5, {}), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::solve
