// Real-time pacing: deadlines come from the step index, lateness is measured against them.
#include "mechsim/cosim/pacer.h"

#include <gtest/gtest.h>

namespace mechsim::cosim {
namespace {

TEST(Pacer, WaitsUntilTheDeadlineOfEachStep) {
  // Step k is due at start + k H / rtf: with H = 10 ms at rtf 2, step 4 is due 20 ms in.
  const std::int64_t start = Pacer::now_ns() + 5'000'000;
  Pacer pacer(start, 0.0, 0.010, 2.0);
  pacer.wait_for_deadline(4);
  const std::int64_t woke = Pacer::now_ns();
  EXPECT_GE(woke, start + 20'000'000);  // never early: clock_nanosleep on an absolute time
  const double late = pacer.published(4);
  EXPECT_GE(late, 0.0);
}

TEST(Pacer, CountsPublicationsLaterThanOneMacroStepAsMissed) {
  // A start 1 s in the past makes steps 0..9 (due within 50 ms of it) all about 1 s late:
  // each is a missed deadline (one step of wall time is 5 ms here).
  Pacer pacer(Pacer::now_ns() - 1'000'000'000, 0.0, 0.010, 2.0);
  for (std::uint64_t k = 0; k < 10; ++k) pacer.published(k);
  RealtimeFigures f = pacer.figures();
  EXPECT_EQ(f.publications, 10);
  EXPECT_EQ(f.missed_deadlines, 10);
  EXPECT_GT(f.lateness_median, 0.9);
  EXPECT_GE(f.lateness_max, f.lateness_p99);
  EXPECT_GE(f.lateness_p99, f.lateness_median);
}

}  // namespace
}  // namespace mechsim::cosim
