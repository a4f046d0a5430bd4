// RollbackSession and its StallResend without processes (docs/faults.md, 'Restart with
// rollback'; stall_resend.h): the follower's writes go to its own topic on an in-process
// domain, where a reader of the test sees what went out, and when it went out again.
#include "node/stall_resend.h"
#include "node_fixture.h"

namespace mechsim::cosim {
namespace {

using testing::FollowerNode;
using testing::header;
using testing::TestClock;

// A partner's reader of follower/state: the steps written since the last look.
struct Partner {
  explicit Partner(FollowerNode& f) : reader(f.participant.create_reader(f.node.topic, *f.node.type->publishes)) {}
  std::vector<std::uint64_t> steps() {
    std::vector<std::uint64_t> out;
    transport::SampleHeader h;
    std::vector<double> v;
    while (reader->take(h, v)) out.push_back(h.step);
    return out;
  }
  std::unique_ptr<transport::SampleReader> reader;
};

std::vector<double> own_sample(const FollowerNode& f, double x) {
  return std::vector<double>(f.node.type->publishes->fields.size(), x);
}

constexpr double kStall = std::chrono::duration<double>(StallResend::kResendAfterStall).count();  // 0.1 s

TEST(RollbackSession, WritesTheOwnSamplesOnce) {
  FollowerNode f;
  Partner partner(f);
  for (std::uint64_t k = 0; k < 3; ++k) {
    f.rollback.write_own(header(k), own_sample(f, 1.0));
    f.rollback.step_taken();
  }
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{0, 1, 2}));
  f.rollback.resend_if_stalled(3);  // no time has passed: no stall
  EXPECT_TRUE(partner.steps().empty());
}

TEST(RollbackSession, WritesTheNewestSamplesAgainAfterAStallOf100ms) {
  FollowerNode f;
  Partner partner(f);
  for (std::uint64_t k = 0; k < 6; ++k) {
    f.rollback.write_own(header(k), own_sample(f, static_cast<double>(k)));
    f.rollback.step_taken();
  }
  ASSERT_EQ(partner.steps().size(), 6u);
  // The clock is the test's: 1 ms short of the stall is no stall, whatever the machine's load.
  TestClock::advance(kStall - 1e-3);
  f.rollback.resend_if_stalled(6);
  EXPECT_TRUE(partner.steps().empty());
  TestClock::advance(2e-3);
  f.rollback.resend_if_stalled(6);
  // The newest kKeptSteady (4), oldest first.
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{2, 3, 4, 5}));
  // Once per kResendAfterStall while the stall lasts, not on every wait.
  f.rollback.resend_if_stalled(6);
  EXPECT_TRUE(partner.steps().empty());
  TestClock::advance(kStall + 1e-3);
  f.rollback.resend_if_stalled(6);
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{2, 3, 4, 5}));
  // A step taken ends the stall.
  f.rollback.write_own(header(6), own_sample(f, 6.0));
  f.rollback.step_taken();
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{6}));
  f.rollback.resend_if_stalled(7);
  EXPECT_TRUE(partner.steps().empty());
}

TEST(RollbackSession, TheLostWriteSeamDropsExactlyThatStep) {
  FollowerNode f(testing::NodeOptions{.lose_write_of_step = 3});
  Partner partner(f);
  for (std::uint64_t k = 0; k < 6; ++k) {
    f.rollback.write_own(header(k), own_sample(f, 1.0));
    f.rollback.step_taken();
  }
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{0, 1, 2, 4, 5}));
  // The lost sample is kept all the same: the stall resend repairs it (what the seam is for).
  TestClock::advance(kStall + 1e-3);
  f.rollback.resend_if_stalled(6);
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{2, 3, 4, 5}));
}

TEST(RollbackSession, AfterAResumeResendsEverythingSinceTheRollbackWithinTheGrace) {
  FollowerNode f;
  Partner partner(f);
  EXPECT_FALSE(f.rollback.within_after_resume(RollbackSession::kForeignWriterGrace));  // never rolled back
  for (std::uint64_t k = 0; k < 10; ++k) f.rollback.write_own(header(k), own_sample(f, 1.0));
  f.rollback.restored(2);
  EXPECT_EQ(f.rollback.rollback_step(), std::optional<std::uint64_t>(2));
  partner.steps();
  f.rollback.go_on(header(2), own_sample(f, 1.0));  // the restored step's sample once more
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{2}));
  EXPECT_TRUE(f.rollback.within_after_resume(RollbackSession::kForeignWriterGrace));
  for (std::uint64_t k = 3; k < 10; ++k) {
    f.rollback.write_own(header(k), own_sample(f, 1.0));
    f.rollback.step_taken();
  }
  partner.steps();
  TestClock::advance(kStall + 1e-3);
  f.rollback.resend_if_stalled(10);
  // Not just the newest 4: all of 2..9, written since the rollback (the steps before it
  // were forgotten at go_on).
  EXPECT_EQ(partner.steps(), (std::vector<std::uint64_t>{2, 3, 4, 5, 6, 7, 8, 9}));
  TestClock::advance(RollbackSession::kForeignWriterGrace);
  EXPECT_FALSE(f.rollback.within_after_resume(RollbackSession::kForeignWriterGrace));
  EXPECT_TRUE(f.rollback.within_after_resume(RollbackSession::kLingeringAfterResume));
}

}  // namespace
}  // namespace mechsim::cosim
