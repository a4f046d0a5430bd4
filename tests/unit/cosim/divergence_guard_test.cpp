// The divergence guard stops growing oscillations (an unstable coupling) and leaves
// physical transients alone.
#include "mechsim/cosim/divergence_guard.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mechsim::cosim {
namespace {

// Feeds y(k) for k < n; returns the step at which the guard fired, or -1.
template <typename F>
long first_alarm(F y, long n) {
  DivergenceGuard guard({"y"});
  for (long k = 0; k < n; ++k) {
    double v = y(k);
    if (guard.check(std::span<const double>(&v, 1))) return k;
  }
  return -1;
}

constexpr double kPi = 3.141592653589793;

TEST(DivergenceGuard, ADecayingOscillationIsLeftAlone) {
  // A lightly damped mode after a step, 8 steps per period, decaying 1 % per period.
  EXPECT_EQ(first_alarm([](long k) { return 1.0 + std::exp(-0.00125 * k) * std::sin(2 * kPi * k / 8.0); }, 20000), -1);
}

TEST(DivergenceGuard, ASteadyOscillationIsLeftAlone) {
  EXPECT_EQ(first_alarm([](long k) { return std::sin(2 * kPi * k / 7.3); }, 20000), -1);
}

TEST(DivergenceGuard, RampsAndStartUpsDoNotOscillateAndAreLeftAlone) {
  EXPECT_EQ(first_alarm([](long k) { return 1e-3 * k * k; }, 20000), -1);       // accelerating
  EXPECT_EQ(first_alarm([](long k) { return std::exp(1e-3 * k); }, 20000), -1);  // exponential, monotonic
}

TEST(DivergenceGuard, AFastGrowingOscillationIsCaughtWithinTwoHundredSteps) {
  // Amplitude x2.5 per 20-step window: the fast criterion needs 8 such windows (+1 to
  // have a previous swing to compare with).
  const long k = first_alarm([](long k) { return std::pow(2.5, k / 20.0) * std::sin(2 * kPi * k / 8.0); }, 10000);
  ASSERT_GE(k, 0);
  EXPECT_LE(k, 9 * 20);
}

TEST(DivergenceGuard, ASlowlyGrowingOscillationIsCaughtToo) {
  // 1.9 % per 20 steps (the NC loop just beyond its limit): below the fast criterion, so
  // the slow one must fire: 15 blocks of 100 steps with > 2 % per block, and 4x in all,
  // which this growth reaches after ~1500 steps; allow the first block and some slack.
  const double rate = std::log(1.019) / 20.0;
  const long k = first_alarm([&](long k) { return 1e-3 * std::exp(rate * k) * std::sin(2 * kPi * k / 9.0); }, 20000);
  ASSERT_GE(k, 0);
  EXPECT_LE(k, 2000 + 200);
}

TEST(DivergenceGuard, NonFiniteValuesAreCaughtAtOnce) {
  EXPECT_EQ(first_alarm([](long k) { return k == 5 ? std::numeric_limits<double>::quiet_NaN() : 0.0; }, 100), 5);
  EXPECT_EQ(first_alarm([](long k) { return k == 3 ? std::numeric_limits<double>::infinity() : 0.0; }, 100), 3);
}

}  // namespace
}  // namespace mechsim::cosim
