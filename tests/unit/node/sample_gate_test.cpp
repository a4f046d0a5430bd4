// SampleGate without processes (docs/faults.md, 'Foreign writers', 'Redundant samples',
// 'Plausible samples' in docs/dds.md): the test writes the cam's samples itself, on the
// follower's input topic of an in-process domain, and looks at what reaches the follower's
// input channel (InputChannel::held_samples), what makes it hold and what ends the run.
#include <cmath>
#include <limits>

#include "node_fixture.h"

namespace mechsim::cosim {
namespace {

using testing::cam_sample;
using testing::fails_with;
using testing::failure_of;
using testing::FollowerNode;
using testing::header;
using testing::TestClock;
using transport::NodeError;

// The cam's writer: the one the scene plans for the follower's input.
struct Cam {
  explicit Cam(FollowerNode& f) : writer(f.participant.create_writer(f.edge.topic, *f.edge.type)) {}
  void write(std::uint64_t step, const std::vector<double>& v, std::uint64_t run_id = testing::kRunId) {
    writer->write(header(step, run_id), v);
  }
  std::unique_ptr<transport::SampleWriter> writer;
};

// The steps the follower's input channel holds.
std::vector<std::uint64_t> held_steps(FollowerNode& f) {
  std::vector<std::uint64_t> steps;
  for (const auto& [step, values] : f.stepper.channel(0).held_samples()) steps.push_back(step);
  return steps;
}

double held_speed(FollowerNode& f, std::uint64_t step) {
  return f.stepper.channel(0).held_samples().at(step).at(static_cast<std::size_t>(f.edge.type->field_index("speed")));
}

TEST(SampleGate, TheFollowerReadsTheCamSpeedAndItIsBounded) {
  // The premise of the plausibility cases below: the gate checks `speed` of cam/state.
  FollowerNode f;
  ASSERT_EQ(f.edge.from, "cam");
  ASSERT_EQ(f.edge.topic, "cam/state");
  const int speed = f.edge.type->field_index("speed");
  ASSERT_GE(speed, 0);
  EXPECT_TRUE(std::any_of(f.edge.field_to_input.begin(), f.edge.field_to_input.end(),
                          [&](const auto& m) { return m.first == speed; }));
  EXPECT_EQ(f.edge.type->fields[static_cast<std::size_t>(speed)].max, 1e4);
}

TEST(SampleGate, PassesThePlannedWritersSamplesInSequence) {
  FollowerNode f;
  Cam cam(f);
  for (std::uint64_t k = 0; k < 3; ++k) cam.write(k, cam_sample(f, 3.0 + static_cast<double>(k)));
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0, 1, 2}));
  EXPECT_EQ(held_speed(f, 2), 5.0);  // the values as written (f64: exact)
  EXPECT_FALSE(f.gate.hold());
  EXPECT_FALSE(f.gate.holding());
}

TEST(SampleGate, DropsASampleOfAnotherRun) {
  FollowerNode f;
  Cam cam(f);
  cam.write(0, cam_sample(f, 3.0), testing::kRunId + 1);  // a stale run on a reused domain
  f.gate.drain();
  EXPECT_TRUE(held_steps(f).empty());
  // The stream of this run is not disturbed by it: its step 0 is still the one due.
  cam.write(0, cam_sample(f, 3.0));
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0}));
}

TEST(SampleGate, DropsARepeatOfAStepWithTheSameValues) {
  // A stalled partner writes its newest samples again (StallResend): the copy is dropped.
  FollowerNode f;
  Cam cam(f);
  cam.write(0, cam_sample(f, 3.0));
  cam.write(1, cam_sample(f, 4.0));
  cam.write(0, cam_sample(f, 3.0));
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0, 1}));
  EXPECT_EQ(held_speed(f, 0), 3.0);
}

TEST(SampleGate, RefusesARepeatOfAStepWithOtherValuesAsForeignData) {
  FollowerNode f;
  Cam cam(f);
  cam.write(0, cam_sample(f, 3.0));
  cam.write(1, cam_sample(f, 4.0));
  cam.write(0, cam_sample(f, 3.5));
  EXPECT_TRUE(fails_with([&] { f.gate.drain(); }, NodeError::foreign_data, {"two different samples for step 0"}));
}

TEST(SampleGate, TakesAStepAheadFromTheOnePlannedWriter) {
  // The reliable stream skipped a step (docs/faults.md): taken with a warning; the skipped
  // step, when it comes after all, is taken too (still needed, not yet held).
  FollowerNode f;
  Cam cam(f);
  cam.write(0, cam_sample(f, 3.0));
  cam.write(2, cam_sample(f, 5.0));
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0, 2}));
  cam.write(1, cam_sample(f, 4.0));
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0, 1, 2}));
}

TEST(SampleGate, RefusesAStepOutOfSequenceWhileASecondWriterIsMatched) {
  FollowerNode f;
  Cam cam(f);
  Cam intruder(f);
  cam.write(0, cam_sample(f, 3.0));
  intruder.write(5, cam_sample(f, 3.0));
  EXPECT_TRUE(fails_with([&] { f.gate.drain(); }, NodeError::foreign_data,
                         {"step 5 arrived where step 1 was due", "2 writer(s) matched"}));
}

TEST(SampleGate, RefusesANonFiniteValueAsImplausibleInput) {
  FollowerNode f;
  Cam cam(f);
  cam.write(0, cam_sample(f, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(fails_with([&] { f.gate.drain(); }, NodeError::implausible_input,
                         {"topic 'cam/state' from participant 'cam', step 0", "speed = nan"}));
}

TEST(SampleGate, RefusesAValueOutsideTheFieldBoundsAsImplausibleInput) {
  FollowerNode f;
  Cam cam(f);
  cam.write(0, cam_sample(f, 1e4));  // the bound itself is plausible
  cam.write(1, cam_sample(f, 1.0001e4));
  EXPECT_TRUE(fails_with([&] { f.gate.drain(); }, NodeError::implausible_input, {"step 1"}));
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0}));
}

TEST(SampleGate, AnImplausibleValueWhileASecondWriterIsMatchedIsForeignData) {
  // Most likely not the partner's sample at all.
  FollowerNode f;
  Cam cam(f);
  Cam intruder(f);
  intruder.write(0, cam_sample(f, 2e4));
  EXPECT_TRUE(fails_with([&] { f.gate.drain(); }, NodeError::foreign_data, {"an implausible sample for step 0"}));
}

TEST(SampleGate, HoldsForASecondWriterAndFailsOnceItOutstaysTheGrace) {
  FollowerNode f;
  Cam cam(f);
  const Cam intruder(f);  // a second writer on cam/state, silent
  cam.write(0, cam_sample(f, 3.0));
  f.gate.drain();  // takes a sample: looks at the writers, and starts the hold
  EXPECT_TRUE(f.gate.holding());
  EXPECT_TRUE(f.gate.hold());
  // Just within the grace (4 s) the node still holds; the clock is the test's, so the
  // margin of 10 ms is exact, not a race.
  TestClock::advance(RollbackSession::kForeignWriterGrace - 0.01);
  EXPECT_TRUE(f.gate.hold());
  TestClock::advance(0.02);
  EXPECT_TRUE(fails_with([&] { f.gate.hold(); }, NodeError::foreign_data,
                         {"topic 'cam/state' (the scene's only writer is participant 'cam')",
                          "more than one writer for 4 s", "domain " + std::to_string(f.domain)}));
}

TEST(SampleGate, EndsTheHoldWhenTheSecondWriterGoes) {
  // A dead process's writer lingers until its lease runs out, then goes: no failure.
  FollowerNode f;
  Cam cam(f);
  auto lingering = std::make_unique<Cam>(f);
  cam.write(0, cam_sample(f, 3.0));
  f.gate.drain();
  ASSERT_TRUE(f.gate.hold());
  TestClock::advance(2.0);
  lingering.reset();
  EXPECT_FALSE(f.gate.hold());
  EXPECT_FALSE(f.gate.holding());
  TestClock::advance(RollbackSession::kForeignWriterGrace);
  EXPECT_FALSE(f.gate.hold());
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0}));
}

TEST(SampleGate, DropsTheTwinCopyOfAStepAlreadyThere) {
  FollowerNode f(testing::NodeOptions{.redundant = true, .lose_write_of_step = std::nullopt});
  ASSERT_NE(f.io.twin_input(0), nullptr);
  Cam cam(f);
  auto twin = f.participant.create_redundant_writer(f.edge.topic, *f.edge.type);
  cam.write(0, cam_sample(f, 3.0));
  twin->write(header(0), cam_sample(f, 3.0));  // the same step's copy
  twin->write(header(1), cam_sample(f, 4.0));  // arrives before the reliable one
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0, 1}));
  cam.write(1, cam_sample(f, 4.0));  // the reliable copy, now the duplicate
  f.gate.drain();
  EXPECT_EQ(held_steps(f), (std::vector<std::uint64_t>{0, 1}));
  EXPECT_EQ(held_speed(f, 1), 4.0);
  EXPECT_FALSE(f.gate.hold());  // one writer on each topic: no hold
}

TEST(SampleGate, RefusesATwinCopyWithOtherValuesAsForeignData) {
  FollowerNode f(testing::NodeOptions{.redundant = true, .lose_write_of_step = std::nullopt});
  Cam cam(f);
  auto twin = f.participant.create_redundant_writer(f.edge.topic, *f.edge.type);
  cam.write(0, cam_sample(f, 3.0));
  twin->write(header(0), cam_sample(f, 3.25));
  EXPECT_TRUE(fails_with([&] { f.gate.drain(); }, NodeError::foreign_data, {"topic 'cam/state/redundant'"}));
}

}  // namespace
}  // namespace mechsim::cosim
