// Root finding on the block's event functions: a bouncing ball, and the chattering guard.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/solve/block_integrator.h"

namespace mechsim::solve {
namespace {

constexpr double kGravity = 9.81;

// Height h and velocity v of a ball; at h = 0 while falling, v -> -e v.
class BouncingBall final : public models::Block {
 public:
  explicit BouncingBall(double restitution) : Block("test_bouncing_ball"), restitution_(restitution) {
    declare_state("h", "m");
    declare_state("v", "m/s");
    declare_output("h", "m");
  }
  void derivatives(double, std::span<const double> x, std::span<const double>,
                   std::span<double> dxdt) const override {
    dxdt[0] = x[1];
    dxdt[1] = -kGravity;
  }
  void calc_outputs(double, std::span<const double> x, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = x[0];
  }
  int num_event_functions() const override { return 1; }
  models::Crossing event_direction(int) const override { return models::Crossing::falling; }
  void event_functions(double, std::span<const double> x, std::span<const double>,
                       std::span<double> g) const override {
    g[0] = x[0];
  }
  bool handle_events(double, std::span<double> x, std::span<const double>,
                     std::span<const int> crossed) override {
    if (crossed[0] == 0) return false;
    x[0] = 0.0;  // on the floor
    x[1] = -restitution_ * x[1];
    return true;
  }

 private:
  double restitution_;
};

class EventsEveryMethod : public ::testing::TestWithParam<Method> {};

INSTANTIATE_TEST_SUITE_P(Solve, EventsEveryMethod,
                         ::testing::Values(Method::cvode_bdf, Method::cvode_adams,
                                           Method::arkode_erk, Method::arkode_dirk));

TEST_P(EventsEveryMethod, BouncingBallHitsTheAnalyticBounceTimes) {
  const double h0 = 1.0, restitution = 0.8, t_end = 3.0;
  BouncingBall ball(restitution);
  SolverOptions options;
  options.method = GetParam();
  options.rtol = 1e-10;
  options.atol = 1e-12;
  BlockIntegrator integrator(ball, options, 0.0, std::vector<double>{h0, 0.0});

  // First impact after a free fall from h0, then flights of 2 e^k v1 / g.
  std::vector<double> expected;
  const double v1 = std::sqrt(2.0 * kGravity * h0);
  for (double t = v1 / kGravity, v = v1; t < t_end; v *= restitution, t += 2.0 * v / kGravity)
    expected.push_back(t);
  ASSERT_EQ(expected.size(), 6u);

  for (int k = 1; k <= 60; ++k) integrator.advance_to(k * 0.05, {});  // events inside macro steps
  const std::vector<EventRecord> events = integrator.take_events();

  // The trajectory is piecewise quadratic in t, which every method reproduces up to its
  // tolerance-controlled start-up error after each restart (rtol = 1e-10), and the roots
  // are located to ~100 ulp of t. A bounce time inherits the error of all earlier flights
  // (each ~rtol relative), so 6 bounces stay near 1e-9 relative at worst; 1e-8 is the
  // ceiling. Skipping or mislocating a bounce shifts the times by ~0.1 s.
  ASSERT_EQ(events.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_NEAR(events[k].t, expected[k], 1e-8 * expected[k]) << "bounce " << k;
    EXPECT_EQ(events[k].function_index, 0);
    EXPECT_EQ(events[k].direction, -1);
  }
  EXPECT_EQ(integrator.stats().roots_found, static_cast<long>(expected.size()));
  EXPECT_EQ(integrator.stats().restarts, static_cast<long>(expected.size()));
  EXPECT_TRUE(integrator.take_events().empty());  // taken once
  EXPECT_GE(integrator.state()[0], -1e-9);  // never found below the floor beyond tolerance
}

// x' = -1 with an event at x = 0 whose handler puts x back just above zero: without a
// guard the integrator would find the same crossing again and again at the same instant.
class Chatterer final : public models::Block {
 public:
  Chatterer() : Block("test_chatterer") {
    declare_state("x", "1");
    declare_output("x", "1");
  }
  void derivatives(double, std::span<const double>, std::span<const double>,
                   std::span<double> dxdt) const override {
    dxdt[0] = -1.0;
  }
  void calc_outputs(double, std::span<const double> x, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = x[0];
  }
  int num_event_functions() const override { return 1; }
  void event_functions(double, std::span<const double> x, std::span<const double>,
                       std::span<double> g) const override {
    g[0] = x[0];
  }
  bool handle_events(double, std::span<double> x, std::span<const double>,
                     std::span<const int>) override {
    ++handled;
    x[0] = 1e-13;
    return true;
  }
  int handled = 0;
};

TEST(Events, RepeatedEventAtTheSameInstantIsLetPass) {
  Chatterer block;
  BlockIntegrator integrator(block, SolverOptions{}, 0.0, std::vector<double>{0.5});
  integrator.advance_to(1.0, {});
  // Handled exactly up to the limit, then the crossing is let pass and x runs on.
  EXPECT_EQ(block.handled, BlockIntegrator::kMaxSimultaneousEvents);
  EXPECT_EQ(integrator.take_events().size(), static_cast<std::size_t>(BlockIntegrator::kMaxSimultaneousEvents));
  // x = 0.5 - t plus the handler's 5 nudges of 1e-13: every method reproduces a linear
  // solution exactly, so only those nudges and rounding remain.
  EXPECT_NEAR(integrator.state()[0], -0.5, 1e-11);
  EXPECT_EQ(integrator.time(), 1.0);
}

}  // namespace
}  // namespace mechsim::solve
