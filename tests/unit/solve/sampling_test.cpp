// Sampled blocks: discrete_update on the grid t0 + j*Ts, whatever the exchange times.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mechsim/solve/block_integrator.h"

namespace mechsim::solve {
namespace {

constexpr double kSamplePeriod = 1e-3;

// A clock c' = 1 (optionally) plus a discrete counter; each update records when it ran
// and the clock reading at that moment.
class SampledClock final : public models::Block {
 public:
  explicit SampledClock(bool with_clock_state) : Block("test_sampled_clock") {
    if (with_clock_state) declare_state("clock", "s");
    declare_output("count", "1");
  }
  void derivatives(double, std::span<const double>, std::span<const double>,
                   std::span<double> dxdt) const override {
    if (!dxdt.empty()) dxdt[0] = 1.0;
  }
  void calc_outputs(double, std::span<const double>, std::span<const double>,
                    std::span<double> y) const override {
    y[0] = static_cast<double>(update_times.size());
  }
  double sample_time() const override { return kSamplePeriod; }
  void discrete_update(double t, std::span<double> x, std::span<const double>) override {
    update_times.push_back(t);
    clock_at_update.push_back(x.empty() ? t : x[0]);
  }

  std::vector<double> update_times;
  std::vector<double> clock_at_update;
};

// Uneven exchange times in (0, 0.1]: a repeating pattern of chunks, some shorter than Ts,
// some landing on grid points by a different floating-point route (sums) than j*Ts.
std::vector<double> uneven_exchange_times() {
  const double pattern[] = {0.00037, 0.0021, 0.001, 0.0005, 0.00313, 0.0001, 0.00029};
  std::vector<double> times;
  double t = 0.0;
  for (int i = 0; t < 0.1; ++i) {
    t = std::min(t + pattern[i % 7], 0.1);
    times.push_back(t);
  }
  return times;
}

class WithAndWithoutStates : public ::testing::TestWithParam<bool> {};

INSTANTIATE_TEST_SUITE_P(Solve, WithAndWithoutStates, ::testing::Values(false, true));

TEST_P(WithAndWithoutStates, ExactlyOneUpdatePerGridInstantOverUnevenChunks) {
  const bool with_state = GetParam();
  SampledClock block(with_state);
  BlockIntegrator integrator(block, SolverOptions{}, 0.0,
                             with_state ? std::vector<double>{0.0} : std::vector<double>{});
  for (double t : uneven_exchange_times()) integrator.advance_to(t, {});

  // Grid instants 0, 1 ms, ..., 100 ms, all within [0, 0.1]: 101 updates, in order.
  ASSERT_EQ(block.update_times.size(), 101u);
  for (std::size_t j = 0; j < block.update_times.size(); ++j) {
    // The update is labelled with its grid instant (1e-15: rounding of j * Ts only).
    EXPECT_NEAR(block.update_times[j], j * kSamplePeriod, 1e-15);
    // ... and runs when the integrator stands at that instant: the clock state (exact for
    // every method, its solution being linear) reads the instant to within the 1e-12 s
    // slack allowed for reaching a grid point.
    EXPECT_NEAR(block.clock_at_update[j], j * kSamplePeriod, 2e-12) << "update " << j;
  }
  integrator.advance_to(0.1, {});  // no time elapsed: no new update
  EXPECT_EQ(block.update_times.size(), 101u);
}

TEST(Sampling, NoUpdateBeforeItsInstant) {
  SampledClock block(true);
  BlockIntegrator integrator(block, SolverOptions{}, 0.0, std::vector<double>{0.0});
  integrator.advance_to(0.0025, {});
  EXPECT_EQ(block.update_times.size(), 3u);  // 0, 1 ms, 2 ms
  integrator.advance_to(0.003, {});           // lands on 3 ms: done before returning
  EXPECT_EQ(block.update_times.size(), 4u);
  integrator.advance_to(0.0039, {});
  EXPECT_EQ(block.update_times.size(), 4u);
}

TEST(Sampling, ResetToAnEarlierTimeResumesTheGridAfterIt) {
  SampledClock block(true);
  BlockIntegrator integrator(block, SolverOptions{}, 0.0, std::vector<double>{0.0});
  integrator.advance_to(0.0105, {});
  ASSERT_EQ(block.update_times.size(), 11u);  // 0 ... 10 ms
  // Roll back to 5 ms (as a checkpoint restore would): the update at 5 ms belongs to the
  // restored state, so the grid resumes at 6 ms.
  integrator.reset_state(0.005, std::vector<double>{0.005});
  integrator.advance_to(0.0105, {});
  ASSERT_EQ(block.update_times.size(), 16u);  // + 6, 7, 8, 9, 10 ms
  EXPECT_NEAR(block.update_times[11], 0.006, 1e-15);
  EXPECT_NEAR(block.clock_at_update[11], 0.006, 2e-12);  // clock restarted from 5 ms
}

}  // namespace
}  // namespace mechsim::solve
