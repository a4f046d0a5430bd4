// PartitionWatch without processes (docs/faults.md, 'Partitions'): the follower waits for
// the cam's sample of step 0; the test's clock says how long.
#include "node/partition_watch.h"

#include "node_fixture.h"

namespace mechsim::cosim {
namespace {

using testing::fails_with;
using testing::failure_of;
using testing::FollowerNode;
using testing::TestClock;
using transport::NodeError;

constexpr double kGrace = 2.0;  // s, the default faults.partition_grace

TEST(PartitionWatch, AWaitLongerThanTheGraceNamesThePartner) {
  FollowerNode f;
  PartitionWatch watch(f.plan, f.node, kGrace, &TestClock::now);
  watch.check(f.stepper, true, false);  // the wait at step 0 begins
  TestClock::advance(kGrace);
  EXPECT_FALSE(failure_of([&] { watch.check(f.stepper, true, false); }));  // the grace itself is no partition
  TestClock::advance(0.01);
  EXPECT_TRUE(fails_with([&] { watch.check(f.stepper, true, false); }, NodeError::partner_unreachable,
                         {"unreachable: no sample for step 0 for 2.0 s (faults.partition_grace 2 s)",
                          "from participant 'cam' (topic cam/state)"}));
}

TEST(PartitionWatch, AnExcusedWaitDoesNotCount) {
  // A hold for a second writer is no partition: the wait starts again after it.
  FollowerNode f;
  PartitionWatch watch(f.plan, f.node, kGrace, &TestClock::now);
  watch.check(f.stepper, true, false);
  TestClock::advance(0.75 * kGrace);
  watch.excuse();
  TestClock::advance(0.75 * kGrace);  // 1.5 grace since the wait began, 0.75 since the excuse
  EXPECT_FALSE(failure_of([&] { watch.check(f.stepper, true, false); }));
  TestClock::advance(0.5 * kGrace);  // 1.25 grace since the excuse
  EXPECT_TRUE(fails_with([&] { watch.check(f.stepper, true, false); }, NodeError::partner_unreachable));
}

TEST(PartitionWatch, NeitherALenientNorAnUninitialisedWaitCounts) {
  FollowerNode f;
  PartitionWatch watch(f.plan, f.node, kGrace, &TestClock::now);
  watch.check(f.stepper, false, false);  // before the initial outputs: waiting for the start
  TestClock::advance(2 * kGrace);
  EXPECT_FALSE(failure_of([&] { watch.check(f.stepper, false, false); }));
  // Right after a rollback's resume (lenient) the wait restarts on every check.
  watch.check(f.stepper, true, true);
  TestClock::advance(2 * kGrace);
  EXPECT_FALSE(failure_of([&] { watch.check(f.stepper, true, true); }));
  // Counted again from the first strict check on.
  watch.check(f.stepper, true, false);
  TestClock::advance(2 * kGrace);
  EXPECT_TRUE(fails_with([&] { watch.check(f.stepper, true, false); }, NodeError::partner_unreachable));
}

}  // namespace
}  // namespace mechsim::cosim
