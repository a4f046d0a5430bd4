// Reconstruction of a partner's values between exchanges (docs/protocol.md).
#include "mechsim/cosim/input_channel.h"

#include <gtest/gtest.h>

namespace mechsim::cosim {
namespace {

using config::EdgeOrder;
using config::Reconstruction;
constexpr double kH = 0.1;

TEST(InputChannel, JacobiHoldNeedsStepKAndHoldsIt) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::hold, 0.0, kH);
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
  InputChannel c(EdgeOrder::jacobi, Reconstruction::quadratic, 0.0, kH);
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
  InputChannel c(EdgeOrder::jacobi, Reconstruction::linear, 0.0, kH);
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
  InputChannel c(EdgeOrder::gauss_seidel, Reconstruction::hold, 0.0, kH);
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
  InputChannel c(EdgeOrder::jacobi, Reconstruction::hold, 0.0, kH);
  c.initial_values(std::vector<double>{7.0, 8.0});
  std::vector<double> v;
  c.initial_values_at(v);
  EXPECT_EQ(v, (std::vector<double>{7.0, 8.0}));
}

TEST(InputChannel, SamplesArrivingOutOfOrderAreUsedByStep) {
  InputChannel c(EdgeOrder::jacobi, Reconstruction::hold, 0.0, kH);
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

}  // namespace
}  // namespace mechsim::cosim
