// Reconstruction of a partner's values between exchanges (docs/protocol.md).
#include "mechsim/cosim/input_channel.h"

#include <gtest/gtest.h>

namespace mechsim::cosim {
namespace {

using config::EdgeOrder;
using config::Reconstruction;
constexpr double kH = 0.1;

// The uniform grid of H = kH over 10 s.
std::shared_ptr<const StepGrid> uniform() { return std::make_shared<const StepGrid>(config::TimeSpec{0.0, 10.0, kH}); }

TEST(InputChannel, JacobiHoldNeedsStepKAndHoldsIt) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::hold, uniform());
  EXPECT_TRUE(c.ready_for_initial());  // a Jacobi edge never blocks the initial outputs
  EXPECT_FALSE(c.ready_for_step(0));
  c.add(0, {1.0});
  EXPECT_TRUE(c.ready_for_step(0));
  EXPECT_FALSE(c.ready_for_step(1));
  std::vector<double> v;
  c.values_at(0.05, 0, v);
  EXPECT_EQ(v[0], 1.0);
  c.add(1, {3.0});
  c.values_at(0.2, 1, v);  // the end of step 1 -> 2 still holds step 1's value
  EXPECT_EQ(v[0], 3.0);
}

TEST(InputChannel, JacobiQuadraticIsExactOnAParabolaAndStartsAsHoldThenLinear) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::quadratic, uniform());
  auto y = [](double step) { return 1.0 + 2.0 * step + 3.0 * step * step; };  // a parabola in t / H
  std::vector<double> v;
  c.add(0, {y(0)});
  c.values_at(0.05, 0, v);
  EXPECT_EQ(v[0], y(0));  // one sample: hold
  c.add(1, {y(1)});
  c.values_at(0.15, 1, v);
  EXPECT_NEAR(v[0], y(1) + 0.5 * (y(1) - y(0)), 1e-12);  // two samples: linear
  c.add(2, {y(2)});
  c.values_at(0.25, 2, v);  // three: the parabola itself, halfway into step 2 -> 3
  EXPECT_NEAR(v[0], y(2.5), 1e-12);
  c.values_at_step_end(2, v);
  EXPECT_NEAR(v[0], y(3), 1e-12);
  c.discard_before(3);  // step 3 -> 4 still needs steps 1, 2 (and 3)
  c.add(3, {y(3)});
  c.values_at(0.35, 3, v);
  EXPECT_NEAR(v[0], y(3.5), 1e-12);
}

TEST(InputChannel, JacobiLinearExtrapolatesFromTwoSamplesAndStartsAsHold) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::linear, uniform());
  c.add(0, {1.0});
  std::vector<double> v;
  c.values_at(0.05, 0, v);
  EXPECT_EQ(v[0], 1.0);  // only one sample: hold
  c.add(1, {3.0});
  c.values_at(0.15, 1, v);  // halfway into step 1 -> 2: 3 + 0.5 * (3 - 1)
  EXPECT_NEAR(v[0], 4.0, 1e-12);
  c.values_at(0.2, 1, v);
  EXPECT_NEAR(v[0], 5.0, 1e-12);
}

TEST(InputChannel, GaussSeidelWaitsForStepKPlusOneAndInterpolates) {
  InputChannel c(EdgeOrder::gauss_seidel, Reconstruction::hold, uniform());
  EXPECT_FALSE(c.ready_for_initial());
  c.add(0, {2.0});
  EXPECT_TRUE(c.ready_for_initial());
  EXPECT_FALSE(c.ready_for_step(0));
  c.add(1, {4.0});
  EXPECT_TRUE(c.ready_for_step(0));
  std::vector<double> v;
  c.values_at(0.025, 0, v);
  EXPECT_NEAR(v[0], 2.5, 1e-12);
  c.values_at(0.1, 0, v);
  EXPECT_EQ(v[0], 4.0);  // exactly the step-(k+1) sample at t_k+1, not a rounded blend
}

TEST(InputChannel, InitialValuesOfAJacobiEdgeAreTheDeclaredDefaults) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::hold, uniform());
  c.initial_values(std::vector<double>{7.0, 8.0});
  std::vector<double> v;
  c.initial_values_at(v);
  EXPECT_EQ(v, (std::vector<double>{7.0, 8.0}));
}

TEST(InputChannel, SamplesArrivingOutOfOrderAreUsedByStep) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::hold, uniform());
  c.add(2, {20.0});
  c.add(0, {0.0});
  c.add(1, {10.0});
  std::vector<double> v;
  c.values_at(0.1, 1, v);
  EXPECT_EQ(v[0], 10.0);
  c.discard_before(3);
  EXPECT_TRUE(c.ready_for_step(2));
  EXPECT_FALSE(c.ready_for_step(0));
}

// On a grid whose steps differ (a step landing on an event), extrapolation goes through the
// samples' own instants: a parabola in t is reproduced exactly across the short step and
// after it, where extrapolating in step fractions (as if the steps were equal) is not.
TEST(InputChannel, JacobiQuadraticIsExactOnAParabolaInTimeAcrossAShortStep) {
  const double event = 0.23;  // steps: ..., 0.2, 0.23 (short), 0.3, ...
  auto grid = std::make_shared<const StepGrid>(StepGrid::landing_on({0.0, 1.0, kH}, std::vector<double>{event}));
  ASSERT_EQ(grid->time(3), event);
  InputChannel c(EdgeOrder::jacobi, Reconstruction::quadratic, grid);
  auto y = [](double t) { return 1.0 - 4.0 * t + 7.0 * t * t; };
  std::vector<double> v;
  for (std::uint64_t k = 0; k <= 5; ++k) c.add(k, {y(grid->time(k))});
  for (std::uint64_t k = 2; k <= 4; ++k) {  // k = 3 extrapolates from the short step
    const double t_mid = 0.5 * (grid->time(k) + grid->time(k + 1));
    c.values_at(t_mid, k, v);
    EXPECT_NEAR(v[0], y(t_mid), 1e-12) << "step " << k;
    c.values_at_step_end(k, v);
    EXPECT_NEAR(v[0], y(grid->time(k + 1)), 1e-12) << "step " << k;
  }
}

// On an adaptive grid a Jacobi extrapolation does not reach back across an event: at the
// event's instant it holds the sample (the value after the event), one step later it is
// linear through the samples after it, then quadratic again. A slope through the jump would
// carry the jump into the steps after it.
TEST(InputChannel, OnAnAdaptiveGridTheExtrapolationRestartsAfterAnEvent) {
  config::TimeSpec time{0.0, 1.0, 0.1};
  time.adaptive = config::AdaptiveStepSpec{};
  time.adaptive->min = 1e-4;
  time.adaptive->max = 0.1;
  time.adaptive->initial = 0.1;
  auto grid = std::make_shared<const StepGrid>(StepGrid::adaptive(time, {}));
  // Steps of 0.1 to the event at 0.3 (step 3), then 0.01, 0.02, 0.04.
  grid->extend(1, 0.2, false);
  grid->extend(2, 0.3, true);
  grid->extend(3, 0.31, false);
  grid->extend(4, 0.33, false);
  grid->extend(5, 0.37, false);
  ASSERT_TRUE(grid->is_event(3));
  auto before = [](double t) { return 5.0 * t; };
  auto after = [](double t) { return -2.0 + 3.0 * t - 8.0 * t * t; };  // jumps at 0.3
  InputChannel c(EdgeOrder::jacobi, Reconstruction::quadratic, grid);
  for (std::uint64_t k = 0; k <= 5; ++k) {
    const double t = grid->time(k);
    c.add(k, {k < 3 ? before(t) : after(t)});
  }
  std::vector<double> v;
  c.values_at_step_end(3, v);  // step 3 -> 4: only the sample at the event
  EXPECT_EQ(v[0], after(0.3));
  c.values_at_step_end(4, v);  // step 4 -> 5: the line through the samples at 0.3 and 0.31
  EXPECT_NEAR(v[0], after(0.31) + (after(0.31) - after(0.3)) * 2.0, 1e-12);
  c.values_at_step_end(5, v);  // step 5 -> 6: the parabola through the three samples after it
  EXPECT_NEAR(v[0], after(0.37), 1e-12);
  // The step before the event (2 -> 3) still extrapolates the parabola through 0, 0.1, 0.2.
  c.values_at_step_end(2, v);
  EXPECT_NEAR(v[0], before(0.3), 1e-12);
}

TEST(InputChannel, GaussSeidelInterpolatesOverAShortStepByItsOwnLength) {
  auto grid = std::make_shared<const StepGrid>(StepGrid::landing_on({0.0, 1.0, kH}, std::vector<double>{0.23}));
  InputChannel c(EdgeOrder::gauss_seidel, Reconstruction::hold, grid);
  c.add(2, {0.0});
  c.add(3, {3.0});  // at t = 0.23
  std::vector<double> v;
  c.values_at(0.22, 2, v);  // two thirds of the short step 0.2 -> 0.23
  EXPECT_NEAR(v[0], 2.0, 1e-12);
}

}  // namespace
}  // namespace mechsim::cosim
