// The summary's error figures and the naming of known coupling artefacts
// (libs/assess signal_compare.h): a signal one macro step late, a jump crossed late.
#include "mechsim/assess/signal_compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mechsim::assess {
namespace {

constexpr double kH = 1e-3;

std::vector<double> grid(int n) {
  std::vector<double> t(n);
  for (int k = 0; k < n; ++k) t[k] = k * kH;
  return t;
}

TEST(ClassifyError, ASignalOneStepLateIsNamedSo) {
  // r = sin(2π 5 t) sampled at 1 ms, c = r one sample late: the error is H r' at most,
  // 2π 5 · 1e-3 = 0.0314, and c is r shifted exactly: the shifted difference is 0.
  const auto t = grid(1000);
  std::vector<double> r(t.size()), c(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) r[k] = std::sin(2 * M_PI * 5 * t[k]);
  c[0] = r[0];
  for (std::size_t k = 1; k < t.size(); ++k) c[k] = r[k - 1];
  const SignalError e = compare_signal(t, c, r);
  EXPECT_NEAR(e.max_abs, 2 * M_PI * 5 * kH, 2e-4);  // sin' at most 2π5, the chord a little less
  const ErrorCause cause = classify_error(t, c, r);
  EXPECT_TRUE(cause.one_step_late);
  EXPECT_EQ(cause.max_abs_shifted, 0.0);
  EXPECT_FALSE(cause.jump);  // a sine has no jump
  EXPECT_EQ(cause.jumps, 0);
}

TEST(ClassifyError, AJumpCrossedOneStepLateIsFoundWithTheErrorAwayFromIt) {
  // A slow ramp with a step of 5 at t = 0.4 s; the co-simulation sees the step one sample
  // late and carries a small smooth error of 0.01 elsewhere.
  const auto t = grid(1000);
  std::vector<double> r(t.size()), c(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) r[k] = t[k] + (k >= 400 ? 5.0 : 0.0);
  for (std::size_t k = 0; k < t.size(); ++k) c[k] = t[k] + (k >= 401 ? 5.0 : 0.0) + 0.01 * std::sin(t[k] * 7);
  const SignalError e = compare_signal(t, c, r);
  EXPECT_NEAR(e.max_abs, 5.0, 0.011);
  EXPECT_NEAR(e.t_of_max, 0.4, 1e-12);
  const ErrorCause cause = classify_error(t, c, r);
  EXPECT_TRUE(cause.jump);
  EXPECT_NEAR(cause.t_jump, 0.4, 1e-12);
  EXPECT_EQ(cause.jumps, 1);
  // Away from the jump only the smooth error is left: |0.01 sin(7t)| <= 0.01.
  EXPECT_LE(cause.max_abs_away_from_jumps, 0.01);
  EXPECT_GT(cause.max_abs_away_from_jumps, 0.005);
  // Not a whole-signal delay: shifted by one step the smooth part still differs, but the
  // ramp of slope 1 shifted by H adds 1e-3 everywhere: under a fifth of 5.
  EXPECT_TRUE(cause.one_step_late);
}

TEST(ClassifyError, ASmoothDriftHasNoKnownCause) {
  // c = r + a slow drift of up to 0.05: neither a delay nor a jump.
  const auto t = grid(1000);
  std::vector<double> r(t.size()), c(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    r[k] = std::cos(2 * M_PI * t[k]);
    c[k] = r[k] + 0.05 * t[k];
  }
  const ErrorCause cause = classify_error(t, c, r);
  EXPECT_FALSE(cause.one_step_late);
  EXPECT_FALSE(cause.jump);
  EXPECT_EQ(cause.jumps, 0);
  EXPECT_NEAR(cause.max_abs_away_from_jumps, 0.05 * t.back(), 1e-12);
}

}  // namespace
}  // namespace mechsim::assess
