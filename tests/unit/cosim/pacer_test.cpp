// Real-time pacing: deadlines come from the step index, lateness is measured against them.
#include "mechsim/cosim/pacer.h"

#include <gtest/gtest.h>

namespace mechsim::cosim {
namespace {

// H = 10 ms over 100 s.
std::shared_ptr<const StepGrid> uniform_10ms() { return std::make_shared<const StepGrid>(config::TimeSpec{0.0, 100.0, 0.010}); }

TEST(Pacer, WaitsUntilTheDeadlineOfEachStep) {
  // Step k is due at start + k H / rtf: with H = 10 ms at rtf 2, step 4 is due 20 ms in.
  const std::int64_t start = Pacer::now_ns() + 5'000'000;
  Pacer pacer(start, uniform_10ms(), 2.0);
  pacer.wait_for_deadline(4);
  const std::int64_t woke = Pacer::now_ns();
  const std::int64_t due = start + 20'000'000;
  EXPECT_GE(woke, due);  // never early: clock_nanosleep on an absolute time
  const double late = pacer.published(4);
  const std::int64_t after = Pacer::now_ns();
  // The lateness is the publication's time against the deadline: between the wake-up's
  // and the clock read after it (1 ns: the conversion to seconds), and it is what the
  // figures report.
  EXPECT_GE(late, static_cast<double>(woke - due) * 1e-9 - 1e-9);
  EXPECT_LE(late, static_cast<double>(after - due) * 1e-9 + 1e-9);
  EXPECT_EQ(pacer.figures().lateness_max, late);
}

TEST(Pacer, CountsPublicationsLaterThanOneMacroStepAsMissed) {
  // A start 1 s in the past makes steps 0..9 (due within 50 ms of it) all about 1 s late:
  // each is a missed deadline (one step of wall time is 5 ms here).
  Pacer pacer(Pacer::now_ns() - 1'000'000'000, uniform_10ms(), 2.0);
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

namespace mechsim::cosim {
namespace {

TEST(LatenessHistogram, QuantilesAreExactToOneBin) {
  // 1000 samples at (i + 0.5) us, i = 0..999: the exact q-quantile is the ceil(q n)-th
  // sample; the histogram answers with the upper edge of its 1 us bin, never below the
  // exact value and at most one bin above it.
  LatenessHistogram h;
  for (int i = 0; i < 1000; ++i) h.add((i + 0.5) * 1e-6);
  EXPECT_EQ(h.count(), 1000);
  EXPECT_EQ(h.overflow(), 0);
  EXPECT_NEAR(h.quantile(0.5), 500e-6, 1e-12);  // the 500th sample is 499.5 us, in bin [499, 500) us
  EXPECT_NEAR(h.quantile(0.99), 990e-6, 1e-12);
  EXPECT_NEAR(h.max(), 999.5e-6, 1e-15);
  EXPECT_NEAR(h.quantile(1.0), 999.5e-6, 1e-15);  // capped by the exact maximum
}

TEST(LatenessHistogram, BeyondTheLastBinTheQuantileIsTheExactMaximum) {
  // 98 on-time publications and two 50 ms outliers: the 99th percentile lies among the
  // outliers, beyond the 20 ms bins, so the conservative answer is the maximum.
  LatenessHistogram h;
  for (int i = 0; i < 98; ++i) h.add(10e-6);
  h.add(0.050);
  h.add(0.040);
  EXPECT_EQ(h.overflow(), 2);
  EXPECT_NEAR(h.quantile(0.5), 11e-6, 1e-12);
  EXPECT_DOUBLE_EQ(h.quantile(0.99), 0.050);
  EXPECT_DOUBLE_EQ(h.max(), 0.050);
}

TEST(LatenessHistogram, AddingSamplesNeverGrowsItsMemory) {
  LatenessHistogram h;
  const auto* data = h.counts().data();
  for (int i = 0; i < 100000; ++i) h.add(i * 1e-7);
  EXPECT_EQ(h.counts().data(), data);
  EXPECT_EQ(h.counts().size(), LatenessHistogram::kBins);
}

}  // namespace
}  // namespace mechsim::cosim
