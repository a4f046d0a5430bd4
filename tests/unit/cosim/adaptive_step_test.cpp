// The adaptive macro step (step_control.h, docs/accuracy.md "Adaptive macro step"): the
// estimate against hand-computed values, the controller's limits, the agreement rule, the
// growing grid; then whole runs in process: steps land on every kind of scheduled event,
// the run reaches its end exactly, the by-hand stepping (SteppedRun) and the node threads over
// the in-process transport (run_inproc) give the same bytes, and a tighter tolerance takes
// more, shorter steps and a smaller error.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/cosim/step_control.h"
#include "mechsim/cosim/stepped_run.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

namespace fs = std::filesystem;
using config::EdgeOrder;
using config::Reconstruction;

config::AdaptiveStepSpec spec(double tol = 1e-3, double min = 1e-6, double max = 1e-2, double initial = 1e-4) {
  config::AdaptiveStepSpec s;
  s.tolerance = tol;
  s.min = min;
  s.max = max;
  s.initial = initial;
  return s;
}

TEST(CouplingErrorEstimate, AHeldRampIsOffByItsSlopeTimesTheStep) {
  // u = 2 t on [0, 1] s so far: range 2 after t = 1. Held over the step 0.9 -> 1.0, the
  // node used u(0.9) = 1.8 at t = 1.0; the partner's sample is 2.0: e = 0.2 / 2 = 0.1.
  CouplingErrorEstimate est({{EdgeOrder::jacobi, Reconstruction::hold, {0}}});
  est.used_at_step_end(0, 9, 0.9, std::vector<double>{0.0});  // an older step: widens the range
  est.used_at_step_end(0, 10, 1.0, std::vector<double>{1.8});
  EXPECT_FALSE(est.at(10, 1e-2, 0.1).has_value()) << "no estimate before the sample of step 10";
  est.received(0, 10, std::vector<double>{2.0});
  const auto r = est.at(10, 1e-2, 0.1);
  ASSERT_TRUE(r.has_value());
  EXPECT_DOUBLE_EQ(r->ratio, 0.1 / 1e-2);
  EXPECT_EQ(r->order, 1);
  // No step before it to tell a trend: e = K h with K = 0.1 / 0.1 s, so the step whose error
  // is 0.8 tol is 0.8e-2 / 1 = 8 ms.
  EXPECT_NEAR(r->longest, 8e-3, 1e-15);
}

TEST(CouplingErrorEstimate, AHeldSignalWhoseSlopePassesThroughZeroIsPredictedFromItsTrend) {
  // u = (t - 1)^2, scale 1, held, steps of 0.1 s. The step 0.9 -> 1.0 errs by only 0.01
  // (slope -0.1 at its midpoint), the one before by 0.03 (-0.3): K rises by 2 per second.
  // Carried to t = 1.1, where the step after the one under way (0.1 s) starts, K = 0.2, the
  // true slope there, and the error of a step h from there is (0.2 + 2 h / 2) h: 0.8 tol =
  // 8e-3 gives h = (-0.2 + sqrt(0.04 + 0.032)) / 2 = 34.16 ms, where the last step's
  // error alone (K = 0.1) would allow 80 ms and overshoot as the slope grows again.
  CouplingErrorEstimate est({{EdgeOrder::jacobi, Reconstruction::hold, {0}, {1.0}}});
  const auto u = [](double t) { return (t - 1) * (t - 1); };
  est.used_at_step_end(0, 7, 0.7, std::vector<double>{u(0.6)});
  est.used_at_step_end(0, 8, 0.8, std::vector<double>{u(0.7)});
  est.received(0, 8, std::vector<double>{u(0.8)});
  est.used_at_step_end(0, 9, 0.9, std::vector<double>{u(0.8)});
  est.received(0, 9, std::vector<double>{u(0.9)});
  est.used_at_step_end(0, 10, 1.0, std::vector<double>{u(0.9)});
  est.received(0, 10, std::vector<double>{u(1.0)});
  const auto r = est.at(10, 1e-2, 0.1);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->ratio, 0.01 / 1e-2, 1e-12);
  EXPECT_NEAR(r->longest, (-0.2 + std::sqrt(0.04 + 0.032)) / 2, 1e-9);
}

// u = t^2 extrapolated linearly errs by u''/2 times the distances from the instant to the
// two samples used: a (a + a1) on unequal steps, whatever their lengths. So K is the same on
// every step (no trend), and the step after one of length c is the root of K h (h + c) = 0.8 tol.
TEST(CouplingErrorEstimate, ALinearExtrapolationOnUnequalStepsIsMeasuredWithItsReach) {
  CouplingErrorEstimate est({{EdgeOrder::jacobi, Reconstruction::linear, {0}, {100.0}}});
  const double t[] = {-0.1, 0.1, 0.3, 0.4};  // t_0 (never passed in: an equal step assumed) .. t_3
  const auto u = [](double x) { return x * x; };
  for (std::uint64_t k = 1; k <= 3; ++k) {
    // What the node extrapolated to t_k through the samples of t_k-2 and t_k-1.
    const double slope = (u(t[k - 1]) - u(k >= 2 ? t[k - 2] : -0.3)) / (t[k - 1] - (k >= 2 ? t[k - 2] : -0.3));
    const double used = u(t[k - 1]) + slope * (t[k] - t[k - 1]);
    est.used_at_step_end(0, k, t[k], std::vector<double>{used});
    est.received(0, k, std::vector<double>{u(t[k])});
  }
  const auto r = est.at(3, 1e-3, 0.05);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->ratio, 0.1 * 0.3 / 100 / 1e-3, 1e-12);  // e = a (a + a1) = 0.03, scale 100
  // K = 0.03 / 100 / 0.03 = 0.01 on both steps measured: 0.01 h (h + 0.05) = 0.8e-3.
  EXPECT_NEAR(r->longest, (-0.05 + std::sqrt(0.05 * 0.05 + 4 * 0.08)) / 2, 1e-9);
}

TEST(CouplingErrorEstimate, NoStepWhoseReconstructionReachesBackAcrossAnEventIsMeasured) {
  // A load jumps by 10 at the event instant t_5: the step 4 -> 5 (held) and, for a linear
  // reconstruction, also 5 -> 6 use a sample from before it. They measure the jump, not the
  // signal: no estimate; the first step whose samples all lie after it measures again.
  for (const auto rec : {Reconstruction::hold, Reconstruction::linear}) {
    CouplingErrorEstimate est({{EdgeOrder::jacobi, rec, {0}, {10.0}}});
    double held = 0.0;
    for (std::uint64_t k = 1; k <= 8; ++k) {
      const double t = 0.1 * static_cast<double>(k);
      const double sample = k >= 5 ? 10.0 + t : t;  // the partner's step-k sample
      est.used_at_step_end(0, k, t, std::vector<double>{held}, k == 5);
      est.received(0, k, std::vector<double>{sample});
      held = sample;  // hold: what the node uses at t_k+1
      const bool after = k >= 5 + (rec == Reconstruction::hold ? 1u : 2u);  // samples all from t_5 on
      if (k >= 2 && !(k >= 5 && !after)) {
        EXPECT_TRUE(est.at(k, 1e-2, 0.1).has_value()) << "step " << k;
      } else if (k >= 5) {
        EXPECT_FALSE(est.at(k, 1e-2, 0.1).has_value()) << "step " << k << " reaches back across the event";
      }
    }
  }
}

TEST(CouplingErrorEstimate, FieldsTheNodeDoesNotUseAreNoError) {
  CouplingErrorEstimate est({{EdgeOrder::jacobi, Reconstruction::linear, {1}}});
  est.used_at_step_end(0, 2, 0.2, std::vector<double>{0.0, 1.0});
  est.used_at_step_end(0, 3, 0.3, std::vector<double>{0.0, 1.0});
  est.received(0, 3, std::vector<double>{1000.0, 1.0});  // field 0 jumps, but feeds no input
  const auto r = est.at(3, 1e-3, 0.1);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->ratio, 0.0);
  EXPECT_EQ(r->order, 2);
  EXPECT_EQ(r->longest, HUGE_VAL);
}

TEST(CouplingErrorEstimate, AGaussSeidelEdgeMeasuresTheCurvatureItsInterpolationMisses) {
  // u = t^2 at t = 0, 1, 2 (uneven steps would work the same): the line through the first
  // two predicts 2 at t = 2, the sample is 4; scale max(range 4, |u| 4) = 4: e = 0.5.
  CouplingErrorEstimate est({{EdgeOrder::gauss_seidel, Reconstruction::hold, {0}}});
  est.used_at_step_end(0, 1, 0.0, std::vector<double>{0.0});
  est.used_at_step_end(0, 2, 1.0, std::vector<double>{1.0});
  EXPECT_FALSE(est.at(2, 0.1, 1.0).has_value()) << "two samples tell no curvature";
  est.used_at_step_end(0, 3, 2.0, std::vector<double>{4.0});
  const auto r = est.at(3, 0.1, 1.0);
  ASSERT_TRUE(r.has_value());
  EXPECT_DOUBLE_EQ(r->ratio, 0.5 / 0.1);
  EXPECT_EQ(r->order, 2);
}

TEST(StepController, TakesTheEstimatesLongestStepWithinItsLimits) {
  const auto s = spec();
  const auto longest = [](double h) { return CouplingErrorEstimate::Result{0.5, 1, h}; };
  EXPECT_DOUBLE_EQ(propose_step(s, 1e-3, longest(1.7e-3)).step_length, 1.7e-3);
  EXPECT_DOUBLE_EQ(propose_step(s, 1e-3, longest(5e-3)).step_length, 2e-3);    // at most twice the step under way
  EXPECT_DOUBLE_EQ(propose_step(s, 1e-3, longest(1e-5)).step_length, 0.2e-3);  // at least a fifth
  EXPECT_DOUBLE_EQ(propose_step(s, 2e-6, longest(1e-9)).step_length, 1e-6);    // min
  EXPECT_DOUBLE_EQ(propose_step(s, 9e-3, longest(HUGE_VAL)).step_length, 1e-2);  // max
  EXPECT_EQ(propose_step(s, 1e-3, longest(1.7e-3)).error_estimate, 0.5);
  // The first step, a restart, and a node with nothing to estimate yet.
  EXPECT_DOUBLE_EQ(propose_step(s, 0.0, longest(5e-3)).step_length, 1e-4);
  EXPECT_DOUBLE_EQ(propose_step(s, 0.0, std::nullopt).step_length, 1e-4);
  EXPECT_DOUBLE_EQ(propose_step(s, 3e-4, std::nullopt).step_length, 3e-4);
}

StepProposal proposal(double h, double event_time = HUGE_VAL, bool event = false) {
  StepProposal p;
  p.step_length = h;
  p.event_time = event_time;
  p.event = event;
  return p;
}

TEST(StepAgreement, TheSmallestProposalTheNextEventAndTheEnd) {
  StepAgreement a(3, spec(), 1.0);
  const double t = 0.5;
  EXPECT_TRUE(a.add(0, 7, proposal(2e-3)));
  EXPECT_TRUE(a.add(2, 7, proposal(1e-3)));
  EXPECT_FALSE(a.complete(7));
  EXPECT_TRUE(a.add(2, 7, proposal(1e-3))) << "the same proposal twice is a duplicate";
  EXPECT_FALSE(a.add(2, 7, proposal(3e-3))) << "another proposal for the same step is refused";
  EXPECT_EQ(a.missing(7), std::vector<std::size_t>{1}) << "what a node names when it waits too long";
  EXPECT_EQ(a.missing(8), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(a.add(1, 7, proposal(5e-3, 0.5035, true)));
  ASSERT_TRUE(a.complete(7));
  EXPECT_EQ(a.agreed(7, t).t_next, t + 1e-3);
  EXPECT_FALSE(a.agreed(7, t).event);
  // An event before the smallest proposal's end: the step ends on it.
  StepAgreement b(2, spec(), 1.0);
  b.add(0, 0, proposal(1e-3));
  b.add(1, 0, proposal(4e-3, 0.5004, true));
  EXPECT_EQ(b.agreed(0, t).t_next, 0.5004);
  EXPECT_TRUE(b.agreed(0, t).event);
  // An instant that is no event (a replay's recorded instant): landed on, not an event.
  StepAgreement r(2, spec(), 1.0);
  r.add(0, 0, proposal(1e-3));
  r.add(1, 0, proposal(1e-2, 0.5007));
  EXPECT_EQ(r.agreed(0, t).t_next, 0.5007);
  EXPECT_FALSE(r.agreed(0, t).event);
  // An event less than `min` beyond it: landed on rather than left for a sliver.
  StepAgreement c(1, spec(1e-3, 1e-5), 1.0);
  c.add(0, 0, proposal(1e-3, 0.501005, true));
  EXPECT_EQ(c.agreed(0, t).t_next, 0.501005);
  // The end, within `min`: reached exactly.
  StepAgreement d(1, spec(1e-3, 1e-5), 1.0);
  d.add(0, 0, proposal(1e-3));
  EXPECT_EQ(d.agreed(0, 0.999).t_next, 1.0);
  EXPECT_EQ(d.agreed(0, 0.99899).t_next, 0.99899 + 1e-3) << "farther than min from the end";
}

TEST(AdaptiveGrid, GrowsByAgreedInstantsAndRefusesAnotherEnd) {
  config::TimeSpec time;
  time.start = 0.0;
  time.end = 1.0;
  time.adaptive = spec(1e-3, 1e-6, 0.5, 0.1);
  time.step = time.adaptive->max;
  const StepGrid g = StepGrid::adaptive(time, {0.25, 0.75, 2.0});
  EXPECT_TRUE(g.is_adaptive());
  // The first step is `initial`; the nodes' proposals set the later ones.
  EXPECT_EQ(g.steps(), 1u);
  EXPECT_EQ(g.time(1), 0.1);
  EXPECT_TRUE(g.knows_end_of(0));
  EXPECT_FALSE(g.knows_end_of(1));
  g.extend(1, 0.2, false);
  g.extend(1, 0.2, false);  // a second node of the same process agrees the same
  EXPECT_THROW(g.extend(1, 0.3, false), std::logic_error);
  EXPECT_THROW(g.extend(3, 0.3, false), std::logic_error);
  g.extend(2, 0.25, true);
  EXPECT_EQ(g.steps(), 3u);
  EXPECT_TRUE(g.is_event(3));
  EXPECT_FALSE(g.is_event(2));
  EXPECT_EQ(g.step_at(0.25), 3u);
  EXPECT_EQ(g.next_scheduled_event(0.25), 0.75);
  EXPECT_EQ(g.next_scheduled_event(0.75), HUGE_VAL) << "2.0 is past the end";
  EXPECT_FALSE(g.at_end(3));
  g.extend(3, 1.0, false);
  EXPECT_TRUE(g.at_end(4));
  // A first step that would pass an event ends on it.
  time.adaptive->initial = 0.3;
  EXPECT_EQ(StepGrid::adaptive(time, {0.25}).time(1), 0.25);
  EXPECT_TRUE(StepGrid::adaptive(time, {0.25}).is_event(1));
}

// A whole adaptive run stepped by hand; returns its plan's grid instants.
std::vector<double> stepped_instants(SteppedRun& run) {
  run.advance(SteppedRun::kToTheEnd);
  EXPECT_FALSE(run.diverged()) << *run.diverged();
  const StepGrid& g = *run.plan().grid();
  std::vector<double> t;
  for (std::uint64_t k = 0; k <= g.steps(); ++k) t.push_back(g.time(k));
  return t;
}

// Every scheduled event is a step boundary marked as an event; events closer together than
// the smallest step are one, landed on the latest of them (StepGrid::adaptive).
void expect_events_landed(const ScenePlan& plan, const StepGrid& grid) {
  ASSERT_FALSE(plan.scheduled_events().empty());
  const double min = grid.adaptive_spec().min;
  for (const auto& e : plan.scheduled_events()) {
    std::uint64_t k = 0;
    while (k < grid.steps() && grid.time(k) < e.t) ++k;
    ASSERT_LT(grid.time(k) - e.t, min) << e.participant << ": no step boundary at its event t = " << e.t;
    EXPECT_TRUE(grid.is_event(k)) << e.t;
  }
}

TEST(AdaptiveRun, TheCamPressLandsOnEveryFollowerLoadBoundaryAndEndsOnTheEnd) {
  SteppedRun run(testing::shipped_scene("cam_press.yaml"), {"time.step=adaptive", "time.tolerance=1e-3", "time.max=4 ms"});
  const std::vector<double> t = stepped_instants(run);
  expect_events_landed(run.plan(), *run.plan().grid());
  EXPECT_EQ(t.back(), 2.0);
  for (std::size_t k = 1; k < t.size(); ++k) ASSERT_LE(t[k] - t[k - 1], 4e-3 * (1 + 1e-12)) << k;
}

TEST(AdaptiveRun, TheServoSetpointCornersLandOnStepBoundaries) {
  SteppedRun run(testing::shipped_scene("nc_slide_loop.yaml"),
                 {"participants.servo.params.setpoint.start=0.53 ms", "time.end=4 ms", "time.step=adaptive", "time.max=50 us",
                  "time.min=0.1 us"});
  stepped_instants(run);
  expect_events_landed(run.plan(), *run.plan().grid());
}

TEST(AdaptiveRun, TheRatioScheduleLandsOnAStepBoundary) {
  SteppedRun run(testing::shipped_scene("extreme/press_line_ratio_step.yaml"),
                 {"time.end=1 s", "time.step=adaptive", "time.max=4 ms", "time.tolerance=1e-2"});
  stepped_instants(run);
  expect_events_landed(run.plan(), *run.plan().grid());
}

// A sampled controller's ticks (the digital amplifier of nc_slide_loop_1ms, 1 ms) are landed
// on: every tick is a step boundary, no step crosses one, and they are not events (the
// controller goes on from the step before instead of restarting at `initial` each time).
TEST(AdaptiveRun, ASampledAmplifiersTicksLandOnStepBoundariesWithoutRestarts) {
  SteppedRun run(testing::shipped_scene("nc_slide_loop_1ms.yaml"),
                 {"time.end=40 ms", "time.step=adaptive", "time.max=4 ms", "time.tolerance=1e-3"});
  const std::vector<double> t = stepped_instants(run);
  const StepGrid& g = *run.plan().grid();
  const double ts = 1e-3;
  std::size_t k = 0;
  for (long long j = 1; j <= 40; ++j) {
    const double tick = static_cast<double>(j) * ts;  // BlockIntegrator's instants, t0 = 0
    while (k < t.size() && t[k] < tick) ++k;
    ASSERT_LT(k, t.size());
    EXPECT_EQ(t[k], tick) << "tick " << j << " falls inside the step " << t[k - 1] << " .. " << t[k];
    if (!run.plan().scheduled_events().empty() && run.plan().scheduled_events().front().t == tick) continue;
    EXPECT_FALSE(g.is_event(k)) << "tick " << j << " restarted the controller";
  }
  // Not pinned to the ticks alone: the controller shortens steps where the loop moves.
  EXPECT_GT(t.size(), 41u);
}

// Where the cam is driven through the CVT its speed varies, so neither its law's joints nor
// the follower's load boundaries have a time before the run: the cam and the follower predict
// each crossing from the shaft's angle, speed and acceleration at the step before
// (angle_event_prediction.h) and the step boundary lands on it, marked as an event.
TEST(AdaptiveRun, AnglesOfACamWhoseSpeedVariesLandOnStepBoundariesWhereTheShaftReachesThem) {
  SteppedRun run(testing::shipped_scene("press_line.yaml"), {"time.end=1 s", "time.step=adaptive", "time.tolerance=1e-3"});
  ASSERT_TRUE(run.plan().scheduled_events().size() <= 2u) << "the ratio schedule only: no angle is planned";
  const auto& nodes = run.plan().nodes();
  std::size_t cam = 0;
  while (nodes[cam].name() != "cam") ++cam;
  const int angle_output = nodes[cam].block->output_index("angle");
  std::vector<double> angle;
  run.on_publish = [&](std::size_t node, std::uint64_t k, const std::vector<double>& y) {
    if (node != cam) return;
    angle.resize(k + 1);
    angle[k] = y[static_cast<std::size_t>(angle_output)];
  };
  const std::vector<double> t = stepped_instants(run);
  ASSERT_EQ(angle.size(), t.size());
  std::vector<double> events = nodes[cam].block->angle_law_changes();  // 0, 150, 180, 330 deg
  for (const auto& node : nodes)
    for (double a : node.block->angle_events()) events.push_back(a);  // 90, 150 deg
  const StepGrid& grid = *run.plan().grid();
  const double two_pi = 2 * std::numbers::pi;
  // What the prediction may miss: a hundredth of a step's turn (measured: at most 1.7e-5 rad).
  constexpr double kTolerance = 1e-4;  // rad
  int crossings = 0;
  for (std::size_t k = 1; k < t.size(); ++k)
    for (const double a : events) {
      const double target = a + two_pi * std::ceil((angle[k - 1] - a) / two_pi);  // the first at or past angle[k-1]
      if (!(target <= angle[k]) || target == 0.0) continue;
      ++crossings;
      // The boundary next to the crossing lies on it, within what the prediction over two
      // steps misses (its error grows with the jerk times tau^3); without landing it would be
      // off by up to a step's turn, speed * h (10 rad/s * 1 ms here).
      const std::size_t j = angle[k] - target < target - angle[k - 1] ? k : k - 1;
      EXPECT_LT(std::abs(angle[j] - target), kTolerance) << "angle " << a << " at t = " << t[j];
      EXPECT_TRUE(grid.is_event(j)) << "angle " << a << " at t = " << t[j];
    }
  EXPECT_GE(crossings, 8) << "a turn and a half of the cam: 0, 90, 150, 180, 330, 0, 90 deg and more";
}

// A state event (a root the integrator finds: the flexible follower's lift-off and landing)
// cannot be landed on: it is found by taking the step that contains it. The node reports it
// with its next proposal, and the step after the next one (the first the proposals still
// set) starts again from `initial`.
TEST(AdaptiveRun, AStateEventFoundInsideAStepRestartsTheFirstStepStillToBeAgreed) {
  SteppedRun run(testing::shipped_scene("cam_lift_off.yaml"),
                 {"participants.cam.params.speed=150 rpm", "time.end=0.3 s", "time.step=adaptive", "time.tolerance=1e-3", "time.max=4 ms",
                  "time.min=1 us", "time.initial=5 us"});
  const std::vector<double> t = stepped_instants(run);
  std::vector<double> found;
  for (const auto& node : run.plan().nodes())
    for (const auto& e : node.block->take_event_log())
      if (e.kind == "lift_off" || e.kind == "landing") found.push_back(e.t);
  ASSERT_GE(found.size(), 3u) << "at 150 rpm the follower leaves the cam and lands again";
  for (const double te : found) {
    std::size_t k = 1;
    while (k < t.size() && t[k] < te) ++k;  // t_k-1 < te <= t_k
    ASSERT_LT(k + 2, t.size()) << te;
    EXPECT_LE(t[k + 2] - t[k + 1], 5e-6 * (1 + 1e-9)) << "event at " << te << " in the step " << t[k - 1] << " -> " << t[k];
  }
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The node threads over the in-process transport agree on the steps through <node>/step
// and give the bytes of the by-hand stepping, node by node.
// (press_line: the cam is driven through the CVT, so its angles are predicted at run time.)
TEST(AdaptiveRun, NodeThreadsGiveTheBytesOfTheSteppedRun) {
  for (const char* name : {"cam_press.yaml", "press_line.yaml"}) {
    SCOPED_TRACE(name);
    const std::vector<std::string> overrides{"time.step=adaptive", "time.tolerance=1e-3", "time.end=0.5 s"};
    const fs::path dir = fs::temp_directory_path() / ("mechsim-adaptive-" + std::to_string(::getpid()));
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    const config::Scene scene = config::load_scene(testing::shipped_scene(name), overrides);
    for (const char* sub : {"a", "b"}) {
      InprocRunOptions options;
      options.run_dir = (dir / sub).string();
      const InprocRunResult r = run_inproc(scene, options);
      ASSERT_TRUE(r.ok) << r.reason;
    }
    SteppedRun stepped(testing::shipped_scene(name), overrides);
    const std::vector<double> t = stepped_instants(stepped);
    for (const auto& node : stepped.plan().nodes()) {
      const std::string file = node.name() + ".outputs.bin";
      EXPECT_TRUE(slurp(dir / "a" / file) == slurp(dir / "b" / file)) << file << " differs between two runs";
      const OutputLog log = read_output_log((dir / "a" / file).string());
      EXPECT_EQ(log.data[0], t) << node.name() << " logged other instants than the stepped run agreed";
    }
    fs::remove_all(dir);
  }
}

// Max error of the cam's shaft torque against the reference on the run's own instants,
// relative to the reference's range.
double shaft_torque_error(const std::vector<std::string>& overrides, std::size_t* steps) {
  const fs::path dir = fs::temp_directory_path() / ("mechsim-adaptive-err-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const config::Scene scene = config::load_scene(testing::shipped_scene("cam_press.yaml"), overrides);
  InprocRunOptions options;
  options.run_dir = dir.string();
  const InprocRunResult r = run_inproc(scene, options);
  EXPECT_TRUE(r.ok) << r.reason;
  ScenePlan plan = ScenePlan::build(scene);
  const ReferenceRun ref = run_reference_at(plan, run_instants(plan, dir.string()));
  const OutputLog log = read_output_log((dir / "cam.outputs.bin").string());
  fs::remove_all(dir);
  const auto& c = log.data[static_cast<std::size_t>(log.column("shaft_torque"))];
  const auto& y = ref.log.data[static_cast<std::size_t>(ref.log.column("cam.shaft_torque"))];
  double lo = HUGE_VAL, hi = -HUGE_VAL, worst = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    lo = std::min(lo, y[k]);
    hi = std::max(hi, y[k]);
    worst = std::max(worst, std::abs(c[k] - y[k]));
  }
  *steps = y.size() - 1;
  return worst / (hi - lo);
}

TEST(AdaptiveRun, ATighterToleranceTakesMoreStepsForASmallerError) {
  std::size_t loose_steps = 0, tight_steps = 0;
  const double loose = shaft_torque_error({"time.step=adaptive", "time.tolerance=1e-2", "time.max=10 ms"}, &loose_steps);
  const double tight = shaft_torque_error({"time.step=adaptive", "time.tolerance=1e-3", "time.max=10 ms"}, &tight_steps);
  std::printf("[ adaptive ] cam_press shaft torque: tol 1e-2: %zu steps, max error %.3g of range; tol 1e-3: %zu steps, %.3g\n",
              loose_steps, loose, tight_steps, tight);
  EXPECT_GT(tight_steps, loose_steps);
  // A first-order (held) edge decides: ten times the tolerance, at least three times the error.
  EXPECT_LT(tight, loose / 3);
}

}  // namespace
}  // namespace mechsim::cosim
