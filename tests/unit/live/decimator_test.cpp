// The decimator's choice of samples (tools/live/decimator.h), driven with a made-up clock.
#include "decimator.h"

#include <gtest/gtest.h>

#include <vector>

namespace mechsim::live {
namespace {

using Clock = Decimator::Clock;

// A run at 10 kHz of 1 ms steps (10 simulated s per wall s) watched at 50 Hz: after the
// pace is measured (a quarter second) the samples sent are 10 / 50 s = 0.2 s apart in
// simulation time, one per tick, i.e. evenly spaced; before, one per tick as they come.
TEST(Decimator, PicksSamplesEvenlyInSimulationTimeAtMostOncePerTick) {
  Decimator d(50.0);
  const std::byte payload[4]{};
  const auto start = Clock::now();
  std::vector<std::uint64_t> sent;
  TimedSample out;
  std::uint64_t step = 0;
  for (int tick = 0; tick < 100; ++tick) {  // 2 wall seconds
    for (int i = 0; i < 200; ++i, ++step) d.offer(step * 1'000'000, payload);  // 200 steps of 1 ms per 20 ms tick
    if (d.due(start + std::chrono::milliseconds(20 * (tick + 1)), out)) sent.push_back(out.t_ns);
  }
  ASSERT_GE(sent.size(), 50u);
  EXPECT_LE(sent.size(), 100u);  // at most one per tick
  EXPECT_EQ(d.stride_ns(), 200'000'000u);  // 10 s/s / 50 Hz, measured exactly with this clock
  // After the first second every gap is the stride, to one step (1 ms).
  for (std::size_t i = sent.size() / 2; i + 1 < sent.size(); ++i) {
    EXPECT_GE(sent[i + 1] - sent[i], 200'000'000u) << i;
    EXPECT_LE(sent[i + 1] - sent[i], 201'000'000u) << i;
  }
  EXPECT_EQ(d.latest().t_ns, (step - 1) * 1'000'000);
}

// A slow run (one sample per several ticks) sends every sample, once.
TEST(Decimator, SendsEverySampleOfARunSlowerThanTheRate) {
  Decimator d(50.0);
  const std::byte payload[4]{};
  const auto start = Clock::now();
  TimedSample out;
  int sent = 0;
  for (int tick = 0; tick < 100; ++tick) {
    if (tick % 5 == 0) d.offer(static_cast<std::uint64_t>(tick) * 1'000'000, payload);
    if (d.due(start + std::chrono::milliseconds(20 * (tick + 1)), out)) ++sent;
  }
  EXPECT_EQ(sent, 20);
}

// Time going back (a new run, a rollback, a looping bag) starts the choice over from there.
TEST(Decimator, StartsOverWhenTimeGoesBack) {
  Decimator d(50.0);
  const std::byte payload[4]{};
  TimedSample out;
  const auto now = Clock::now();
  d.offer(5'000'000'000, payload);
  ASSERT_TRUE(d.due(now, out));
  d.offer(1'000'000, payload);
  ASSERT_TRUE(d.due(now + std::chrono::milliseconds(20), out));
  EXPECT_EQ(out.t_ns, 1'000'000u);
}

}  // namespace
}  // namespace mechsim::live
