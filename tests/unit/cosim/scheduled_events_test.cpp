// Discontinuities a participant knows before the run (models::Block::scheduled_events) land
// on macro-step boundaries: every node plans the same scene, so every node steps on the
// same grid (step_grid.h) without a message. One test per event kind: a setpoint step, the
// corners of a ramp and of a trapezoid, a ratio-schedule point; then a run in process, whose
// logged row at the setpoint step is the value after it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

namespace fs = std::filesystem;

// The plan's scheduled event times of `participant`.
std::vector<double> events_of(const ScenePlan& plan, const std::string& participant) {
  std::vector<double> times;
  for (const auto& e : plan.scheduled_events())
    if (e.participant == participant) times.push_back(e.t);
  return times;
}

// Every event is an instant of the grid, and the step before it ends there.
void expect_landed(const ScenePlan& plan, const std::vector<double>& times) {
  const StepGrid& grid = *plan.grid();
  for (double t : times) {
    const auto k = grid.step_at(t);
    ASSERT_TRUE(k.has_value()) << "no step boundary at t = " << t;
    EXPECT_EQ(grid.time(*k), t);
    EXPECT_LT(grid.step_length(*k - 1), grid.nominal_step()) << "the step before t = " << t << " was not shortened";
  }
}

// Every event is an instant of the grid (an event on a uniform instant adds no step).
void expect_landed_or_on_grid(const ScenePlan& plan, const std::vector<double>& times) {
  for (double t : times) {
    const auto k = plan.grid()->step_at(t);
    ASSERT_TRUE(k.has_value()) << "no step boundary at t = " << t;
    EXPECT_TRUE(plan.grid()->is_event(*k)) << t;
  }
}

TEST(ScheduledEvents, ASetpointStepOffTheGridLandsOnABoundary) {
  const config::Scene scene = config::load_scene(testing::shipped_scene("nc_slide_loop.yaml"),
                                                 {"participants.servo.params.setpoint.start=0.53 ms", "time.end=2 ms"});
  const ScenePlan plan = ScenePlan::build(scene);  // H = 25 us: 0.53 ms is 21.2 H
  const std::vector<double> times = events_of(plan, "servo");
  ASSERT_EQ(times.size(), 1u);
  EXPECT_DOUBLE_EQ(times[0], 0.53e-3);
  expect_landed(plan, times);
  EXPECT_EQ(plan.grid()->steps(), 81u);  // 80 uniform steps, one of them split
}

TEST(ScheduledEvents, RampAndTrapezoidCornersLand) {
  const config::Scene ramp = config::load_scene(
      testing::shipped_scene("nc_slide_loop.yaml"),
      {"participants.servo.params.setpoint.type=ramp", "participants.servo.params.setpoint.start=0.11 ms",
       "participants.servo.params.setpoint.velocity=0.13 m/s", "time.end=2 ms"});
  const ScenePlan ramp_plan = ScenePlan::build(ramp);
  ASSERT_EQ(events_of(ramp_plan, "servo").size(), 2u);  // start, and 0.1 mm / 0.13 m/s later
  EXPECT_NEAR(events_of(ramp_plan, "servo")[1] - events_of(ramp_plan, "servo")[0], 1e-4 / 0.13, 1e-15);
  expect_landed(ramp_plan, events_of(ramp_plan, "servo"));

  const config::Scene trapezoid = config::load_scene(testing::shipped_scene("nc_slide_move.yaml"),
                                                     {"participants.servo.params.setpoint.start=1.01 ms"});
  const ScenePlan trapezoid_plan = ScenePlan::build(trapezoid);
  // 20 mm at 100 mm/s and 1 m/s^2: accelerate 0.1 s, cruise 0.1 s, decelerate 0.1 s.
  const std::vector<double> corners = events_of(trapezoid_plan, "servo");
  ASSERT_EQ(corners.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(corners[i], 1.01e-3 + 0.1 * i, 1e-12);
  expect_landed(trapezoid_plan, corners);
}

TEST(ScheduledEvents, ARatioScheduleLandsAndPointsOnTheGridAddNoStep) {
  // The shipped schedule jumps at 0.6 s and 1.3 s, on the 1 ms grid: no step is added.
  const config::Scene shipped = config::load_scene(testing::shipped_scene("extreme/press_line_ratio_step.yaml"));
  const ScenePlan on_grid = ScenePlan::build(shipped);
  // Each jump is two schedule rows at one time: one event (printed once by mechsim check).
  EXPECT_EQ(events_of(on_grid, "cvt").size(), 2u);
  EXPECT_TRUE(on_grid.grid()->uniform());
  EXPECT_EQ(on_grid.grid()->steps(), 2000u);
  // Moved by 0.4 ms, both jumps land on boundaries of their own.
  const config::Scene moved = config::load_scene(
      testing::shipped_scene("extreme/press_line_ratio_step.yaml"),
      {"participants.cvt.params.ratio_actuator.schedule[1].t=0.6004 s",
       "participants.cvt.params.ratio_actuator.schedule[2].t=0.6004 s",
       "participants.cvt.params.ratio_actuator.schedule[3].t=1.3004 s",
       "participants.cvt.params.ratio_actuator.schedule[4].t=1.3004 s"});
  const ScenePlan off_grid = ScenePlan::build(moved);
  ASSERT_EQ(events_of(off_grid, "cvt").size(), 2u);
  expect_landed(off_grid, events_of(off_grid, "cvt"));
  EXPECT_EQ(off_grid.grid()->steps(), 2002u);
}

// The press cam turns at 30 rpm: the follower's load boundaries (45, 100, 120, 180, 210 deg)
// are times, 45 and 180 deg on the 1 ms grid (0.25 s, 1 s), the other three not. Each time is
// the first double at which the follower sees the cam angle past the boundary.
TEST(ScheduledEvents, LoadBoundariesAtCamAnglesBecomeTimesOnTheFarSide) {
  const config::Scene scene = config::load_scene(testing::shipped_scene("cam_press.yaml"));
  const ScenePlan plan = ScenePlan::build(scene);
  const std::vector<double> times = events_of(plan, "follower");
  const std::vector<double> degrees{45, 100, 120, 180, 210};
  ASSERT_EQ(times.size(), degrees.size());
  const double speed = 30 * 2 * std::numbers::pi / 60;  // rad/s
  const models::Block& follower = *plan.node("follower").block;
  const auto rotation = plan.node("cam").block->uniform_rotation();
  ASSERT_TRUE(rotation.has_value());
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double boundary = degrees[i] * std::numbers::pi / 180;
    EXPECT_NEAR(times[i], boundary / speed, 1e-12) << degrees[i] << " deg";
    EXPECT_TRUE(follower.angle_event_reached(rotation->angle(times[i]), boundary)) << degrees[i] << " deg";
    EXPECT_FALSE(follower.angle_event_reached(rotation->angle(std::nextafter(times[i], 0.0)), boundary))
        << degrees[i] << " deg";
  }
  expect_landed_or_on_grid(plan, times);
  EXPECT_EQ(plan.grid()->steps(), 2003u);  // three boundaries off the grid
  EXPECT_EQ(plan.grid()->event_count(), 5u);
  // A cam driven through a gear (press_line) turns as its drive does: nothing is planned.
  const config::Scene press_line = config::load_scene(testing::shipped_scene("press_line.yaml"));
  EXPECT_TRUE(events_of(ScenePlan::build(press_line), "follower").empty());
}

// Each event lands a step: a cam at 3 million rpm over the press cam's two seconds would
// schedule 500 000 load boundaries. Refused, naming the participant, before anything runs.
TEST(ScheduledEvents, FarTooManyAreRefusedNamingTheParticipant) {
  const config::Scene scene = config::load_scene(testing::shipped_scene("cam_press.yaml"),
                                                 {"participants.cam.params.speed=3000000 rpm"});
  try {
    ScenePlan::build(scene);
    FAIL() << "accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("participants.follower.params"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 100000 discontinuities"), std::string::npos) << e.what();
  }
}

// Through the product's node loop: the amplifier's logged position reference is 0 up to
// the step before the setpoint step and the full distance at the step's own instant (the
// schedule is right-continuous), where the run's instants include it.
TEST(ScheduledEvents, TheNodesStepOnTheLandedGridAndLogTheValueAfterTheEvent) {
  const config::Scene scene = config::load_scene(testing::shipped_scene("nc_slide_loop.yaml"),
                                                 {"participants.servo.params.setpoint.start=0.53 ms", "time.end=2 ms"});
  const fs::path dir = fs::temp_directory_path() / ("mechsim-scheduled-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  InprocRunOptions options;
  options.run_dir = dir.string();
  const InprocRunResult r = run_inproc(scene, options);
  ASSERT_TRUE(r.ok) << r.reason;
  const std::vector<double> event = events_of(ScenePlan::build(scene), "servo");
  ASSERT_EQ(event.size(), 1u);
  const OutputLog log = read_output_log((dir / "servo.outputs.bin").string());
  fs::remove_all(dir);
  ASSERT_EQ(log.rows(), 82u);  // steps 0 .. 81
  const auto& t = log.data[0];
  const auto& reference = log.data[static_cast<std::size_t>(log.column("position_reference"))];
  const std::size_t at = 22;  // 21 uniform steps of 25 us (0.525 ms), then the event
  EXPECT_EQ(t[at], event[0]);
  EXPECT_EQ(reference[at - 1], 0.0);
  EXPECT_DOUBLE_EQ(reference[at], 1e-4);
  EXPECT_NEAR(t[at + 1], 0.55e-3, 1e-15);  // back on the uniform grid
}

}  // namespace
}  // namespace mechsim::cosim
