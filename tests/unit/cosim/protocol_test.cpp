// The lock-step protocol of two nodes driven by hand (no transport): who waits for what,
// what a Jacobi edge delays, and that results do not depend on the order of events.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <memory>

#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/node_stepper.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

struct TwoNodes {
  explicit TwoNodes(const std::string& path)
      : scene(std::make_unique<config::Scene>(config::load_scene(path))),
        plan(ScenePlan::build(*scene)),
        cam(plan.node("cam"), plan.grid()),
        follower(plan.node("follower"), plan.grid()) {}
  std::unique_ptr<config::Scene> scene;
  ScenePlan plan;
  NodeStepper cam, follower;
};

// Every block output of both nodes at every step, in the order the exchange produced them.
struct Trace {
  std::vector<std::vector<double>> cam, follower;
};

// Runs the exchange to the end. `cam_first` flips which node is offered a step first, so
// that a test can show the outcome does not depend on scheduling.
Trace exchange(TwoNodes& n, bool cam_first) {
  Trace trace;
  std::vector<double> v;
  auto publish_cam = [&] {
    n.follower.channel(0).add(n.cam.step(), v);
    trace.cam.push_back(n.cam.outputs());
  };
  auto publish_follower = [&] {
    n.cam.channel(0).add(n.follower.step(), v);
    trace.follower.push_back(n.follower.outputs());
  };
  n.cam.initialise(v);
  publish_cam();
  n.follower.initialise(v);
  publish_follower();
  while (!n.cam.finished() || !n.follower.finished()) {
    bool progressed = false;
    for (int turn = 0; turn < 2; ++turn) {
      if ((turn == 0) == cam_first) {
        if (n.cam.can_step()) { n.cam.step(v); publish_cam(); progressed = true; }
      } else {
        if (n.follower.can_step()) { n.follower.step(v); publish_follower(); progressed = true; }
      }
    }
    if (!progressed) throw std::runtime_error("deadlock");
  }
  return trace;
}

TEST(Protocol, GaussSeidelEdgeWaitsForThePartnersSameStepAndJacobiForThePrevious) {
  TwoNodes n(testing::shipped_scene("cam_press.yaml"));
  std::vector<double> v;
  // follower <- cam is Gauss-Seidel: even the initial outputs wait for cam's step 0.
  EXPECT_FALSE(n.follower.can_initialise());
  // cam <- follower is Jacobi: its initial outputs use the declared initial value.
  ASSERT_TRUE(n.cam.can_initialise());
  n.cam.initialise(v);
  n.follower.channel(0).add(0, v);
  ASSERT_TRUE(n.follower.can_initialise());
  n.follower.initialise(v);
  // cam 0 -> 1 needs follower's step 0 (Jacobi): not yet delivered.
  EXPECT_FALSE(n.cam.can_step());
  n.cam.channel(0).add(0, v);
  EXPECT_TRUE(n.cam.can_step());
  // follower 0 -> 1 needs cam's step 1 (Gauss-Seidel).
  EXPECT_FALSE(n.follower.can_step());
  n.cam.step(v);
  n.follower.channel(0).add(1, v);
  EXPECT_TRUE(n.follower.can_step());
}

TEST(Protocol, JacobiHoldDelaysThePartnersOutputByExactlyOneStep) {
  TwoNodes n(testing::shipped_scene("cam_press.yaml"));
  Trace trace = exchange(n, true);
  const int shaft_torque = n.plan.node("cam").block->output_index("shaft_torque");
  const int drive_torque = n.plan.node("follower").block->output_index("drive_torque");
  ASSERT_EQ(trace.cam.size(), trace.follower.size());
  EXPECT_EQ(trace.cam[0][shaft_torque], 0.0);  // the input's default before any sample
  for (std::size_t k = 0; k + 1 < trace.cam.size(); ++k)
    ASSERT_EQ(trace.cam[k + 1][shaft_torque], trace.follower[k][drive_torque]) << "step " << k;
}

TEST(Protocol, ResultsDoNotDependOnSchedulingAndRepeatBitForBit) {
  TwoNodes a(testing::shipped_scene("cam_press.yaml"));
  TwoNodes b(testing::shipped_scene("cam_press.yaml"));
  Trace first = exchange(a, true);
  Trace second = exchange(b, false);
  ASSERT_EQ(first.follower.size(), second.follower.size());
  for (std::size_t k = 0; k < first.follower.size(); ++k) {
    ASSERT_EQ(0, std::memcmp(first.follower[k].data(), second.follower[k].data(), first.follower[k].size() * sizeof(double)));
    ASSERT_EQ(0, std::memcmp(first.cam[k].data(), second.cam[k].data(), first.cam[k].size() * sizeof(double)));
  }
}

TEST(Protocol, GaussSeidelCoSimulationReproducesTheMonolithicContactForce) {
  TwoNodes n(testing::shipped_scene("cam_press.yaml"));
  Trace trace = exchange(n, true);
  auto ref_scene = std::make_unique<config::Scene>(config::load_scene(testing::shipped_scene("cam_press.yaml")));
  ScenePlan ref_plan = ScenePlan::build(*ref_scene);
  ReferenceRun ref = run_reference(ref_plan);
  const auto& n_ref = ref.log.data[ref.log.column("follower.contact_force")];
  const int n_col = n.plan.node("follower").block->output_index("contact_force");
  ASSERT_EQ(n_ref.size(), trace.follower.size());
  const double range = *std::max_element(n_ref.begin(), n_ref.end()) - *std::min_element(n_ref.begin(), n_ref.end());
  double worst = 0;
  for (std::size_t k = 0; k < n_ref.size(); ++k) worst = std::max(worst, std::abs(trace.follower[k][n_col] - n_ref[k]));
  // Same blocks, and on the Gauss-Seidel edge the follower sees the cam's step-k values
  // at step k, as in the monolithic run; the cam angle is a closed function of t in both.
  // So the two agree to rounding; an off-by-one step would be off by up to the whole
  // range (loads jump by 330 N). 1e-9 of the range separates the two cases.
  EXPECT_LT(worst, 1e-9 * range);
}

}  // namespace
}  // namespace mechsim::cosim
