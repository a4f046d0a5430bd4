// The macro-step instants every node, the reference and the tools share (step_grid.h).
#include "mechsim/cosim/step_grid.h"

#include <gtest/gtest.h>

#include <vector>

namespace mechsim::cosim {
namespace {

TEST(StepGrid, UniformInstantsAreComputedFromTheIndexNotAccumulated) {
  const StepGrid grid(config::TimeSpec{0.5, 2.5, 1e-3});
  EXPECT_TRUE(grid.uniform());
  EXPECT_EQ(grid.steps(), 2000u);
  double accumulated = 0.5;
  for (std::uint64_t k = 1; k <= grid.steps(); ++k) accumulated += 1e-3;
  EXPECT_EQ(grid.time(2000), 0.5 + 2000.0 * 1e-3);  // the index formula, bit for bit
  EXPECT_NE(grid.time(2000), accumulated);           // which accumulation is not
  EXPECT_EQ(grid.step_length(7), 1e-3);
  EXPECT_EQ(grid.step_at(grid.time(1234)), 1234u);
  EXPECT_FALSE(grid.step_at(0.5 + 1.5e-3).has_value());
  EXPECT_FALSE(grid.step_at(3.0).has_value());
}

TEST(StepGrid, AnEventBecomesABoundaryAndTheStepBeforeItEndsThere) {
  const std::vector<double> events{0.555, 0.25, 7.0, -1.0};  // unsorted; two outside the run
  const StepGrid grid = StepGrid::landing_on({0.0, 1.0, 0.1}, events);
  EXPECT_FALSE(grid.uniform());
  EXPECT_EQ(grid.steps(), 12u);  // 10 uniform steps, two of them split
  const std::vector<double> expected{0.0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.5, 0.555, 0.6, 0.7, 0.8, 0.9, 1.0};
  for (std::uint64_t k = 0; k <= grid.steps(); ++k) EXPECT_NEAR(grid.time(k), expected[k], 1e-15) << k;
  // The uniform instants stay the index formula's (a node and the reference agree on them).
  EXPECT_EQ(grid.time(4), 3 * 0.1);
  EXPECT_NEAR(grid.step_length(2), 0.05, 1e-15);
  EXPECT_EQ(grid.step_at(0.555), 7u);
  EXPECT_TRUE(grid.is_event(3));
  EXPECT_TRUE(grid.is_event(7));
  EXPECT_FALSE(grid.is_event(4));
  EXPECT_EQ(grid.end(), 1.0);
}

TEST(StepGrid, EventsOnOrNearlyOnAUniformInstantAddNoStep) {
  // An event on a uniform instant marks it and the grid stays uniform (bit for bit the
  // scene's own). 1e-9 s past an instant is a hundred-millionth of H = 0.1 s: not worth a
  // step of its own, it takes the instant's place (the event's double is the first on its
  // far side). Two events closer than that merge.
  const StepGrid exact = StepGrid::landing_on({0.0, 1.0, 0.1}, std::vector<double>{3 * 0.1});
  EXPECT_TRUE(exact.uniform());
  EXPECT_TRUE(exact.is_event(3));
  EXPECT_FALSE(exact.is_event(4));

  const std::vector<double> events{0.1 + 0.2, 0.5 + 1e-9, 0.71, 0.71 + 1e-12};
  const StepGrid grid = StepGrid::landing_on({0.0, 1.0, 0.1}, events);
  EXPECT_EQ(grid.steps(), 11u);
  EXPECT_EQ(grid.time(5), 0.5 + 1e-9);
  EXPECT_EQ(grid.step_at(0.71), 8u);
  EXPECT_EQ(grid.event_count(), 3u);
  for (std::uint64_t k : {3u, 5u, 8u}) EXPECT_TRUE(grid.is_event(k)) << k;
  EXPECT_TRUE(StepGrid::landing_on({0.0, 1.0, 0.1}, std::vector<double>{}).uniform());
}

// A landed grid keeps the uniform one and its few changes, never a double per step: a
// scene of 10^12 steps with two events builds at once (one double per step would be 8 TB).
TEST(StepGrid, AHugeGridWithEventsIsKeptAsItsChanges) {
  const StepGrid grid = StepGrid::landing_on({0.0, 1e6, 1e-6}, std::vector<double>{0.25e-6 + 3.0, 5e5});
  EXPECT_EQ(grid.steps(), 1'000'000'000'001u);  // 10^12 uniform steps, one event off the grid
  const std::uint64_t inserted = 3'000'001u;    // after the instants 0 .. 3 s
  EXPECT_EQ(grid.time(inserted), 0.25e-6 + 3.0);
  EXPECT_EQ(grid.time(inserted + 1), 3'000'001 * 1e-6);  // the uniform instants go on, shifted by one
  EXPECT_EQ(grid.step_at(0.25e-6 + 3.0), inserted);
  EXPECT_TRUE(grid.is_event(inserted));
  const auto half = grid.step_at(5e5);  // on a uniform instant: marked, no step added
  ASSERT_TRUE(half.has_value());
  EXPECT_EQ(*half, 500'000'000'001u);
  EXPECT_TRUE(grid.is_event(*half));
  EXPECT_EQ(grid.end(), 1e12 * 1e-6);
}

}  // namespace
}  // namespace mechsim::cosim
