// FMU state in checkpoints (docs/fmi.md "FMU state, rollback and the adaptive step"): the
// importer's get/set/serialize round trip on the test FMUs' binaries, the blocks'
// save/restore_discrete_state as a node's checkpoint and a restarted process use them, the
// refusal for an FMU without the flags, time events landed on by the model-exchange
// block, and <ModelStructure> dependencies as the blocks' feedthrough.
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/fmi/co_simulation_block.h"
#include "mechsim/fmi/model_exchange_block.h"
#include "mechsim/models/nc/servo_amplifier_block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::fmi {
namespace {

using test::test_fmu;

std::shared_ptr<const FmuArchive> open(const std::string& stem) {
  return std::make_shared<const FmuArchive>(FmuLabel{test_fmu(stem), "p"});
}

std::string refusal_text(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(not refused)";
}

solve::SolverOptions tight() {
  solve::SolverOptions o;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  return o;
}

// --- the instance: get, serialize, deserialize, set --------------------------------------

class StateRoundTrip : public ::testing::TestWithParam<const char*> {};

// The servo amplifier stepped to 10 ms, its state saved as bytes, stepped on to 20 ms; then
// the bytes restored, into the same instance and into a fresh one (what a restarted node
// process does), and stepped again to 20 ms with the same inputs: the outputs must be the
// same doubles (the FMU's state is its whole model struct; nothing else may differ). A
// restore that missed the integrator state would be volts off after a setpoint step.
TEST_P(StateRoundTrip, BytesPutTheFmuBackExactly) {
  const auto archive = open(GetParam());
  const ModelDescription& md = archive->description();
  const auto vr = [&](const char* name) { return md.find_variable(name)->value_reference; };
  const auto start = [&](FmuInstance& fmu) {
    fmu.enter_initialization(0.0, 1.0);
    fmu.set_real(vr("step_distance"), 1e-3);
    fmu.exit_initialization();
  };
  const auto run = [&](FmuInstance& fmu, int from, int to) {
    for (int k = from; k < to; ++k) {
      fmu.set_real(vr("tacho_voltage"), 2.0 * std::sin(0.1 * k));
      fmu.set_real(vr("spindle_angle"), 0.05 * k);
      fmu.do_step(k * 1e-3, 1e-3);
    }
    return std::vector<double>{fmu.get_real(vr("armature_voltage")), fmu.get_real(vr("velocity_error"))};
  };
  auto fmu = FmuInstance::create(*archive, InterfaceKind::co_simulation, "amp");
  start(*fmu);
  run(*fmu, 0, 10);
  const std::vector<std::uint8_t> bytes = fmu->save_state();
  EXPECT_GT(bytes.size(), 0u);
  const std::vector<double> expected = run(*fmu, 10, 20);
  fmu->restore_state(bytes);
  EXPECT_EQ(run(*fmu, 10, 20), expected);
  auto fresh = FmuInstance::create(*archive, InterfaceKind::co_simulation, "amp");
  start(*fresh);
  fresh->restore_state(bytes);
  EXPECT_EQ(run(*fresh, 10, 20), expected);
  // Not restored, the fresh instance is elsewhere: the comparison can fail.
  auto other = FmuInstance::create(*archive, InterfaceKind::co_simulation, "amp");
  start(*other);
  EXPECT_NE(run(*other, 10, 20), expected);
}

INSTANTIATE_TEST_SUITE_P(TestFmus, StateRoundTrip, ::testing::Values("servo_amplifier_fmi2_cs", "servo_amplifier_fmi3_cs"));

TEST(FmuState, AnFmuWithoutTheFlagsIsRefusedNamingThem) {
  const auto lag2 = open("lag_fmi2_cs");
  EXPECT_EQ(missing_state_capabilities(lag2->description(), InterfaceKind::co_simulation),
            "canGetAndSetFMUstate and canSerializeFMUstate");
  EXPECT_EQ(missing_state_capabilities(open("lag_fmi3_me")->description(), InterfaceKind::model_exchange),
            "canGetAndSetFMUState and canSerializeFMUState");
  EXPECT_EQ(missing_state_capabilities(open("servo_amplifier_fmi3_me")->description(), InterfaceKind::model_exchange), "");
  auto fmu = FmuInstance::create(*lag2, InterfaceKind::co_simulation, "lag");
  fmu->enter_initialization(0.0, 1.0);
  fmu->exit_initialization();
  EXPECT_NE(refusal_text([&] { fmu->save_state(); })
                .find("(participant 'p'): cannot save its state: its co-simulation interface does not declare "
                      "canGetAndSetFMUstate and canSerializeFMUstate"),
            std::string::npos);
  // The blocks: saving works (nothing of the FMU's own is held), restoring is refused.
  CoSimulationBlock block(lag2, {}, 0.0, 1.0, 1e-3);
  const auto saved = block.save_discrete_state();
  EXPECT_NE(refusal_text([&] { block.restore_discrete_state(saved); }).find("cannot restore its state"), std::string::npos);
}

// --- the blocks' checkpoints -----------------------------------------------------------

// What NodeStepper::restore does in a restarted process: a new block and integrator at t0,
// the t0 sample taken, then the checkpoint's time, continuous state and discrete state.
struct Restored {
  std::unique_ptr<models::Block> block;
  std::unique_ptr<solve::BlockIntegrator> integrator;
};

class CoSimulationCheckpoint : public ::testing::TestWithParam<const char*> {};

// The servo amplifier's co-simulation block, 1 ms samples, checkpointed at 25 ms and run on
// to 60 ms; a new block restored from the checkpoint runs 25 -> 60 ms to the same doubles at
// every millisecond (held outputs, the last sample instant and the FMU's own integrator
// state all come back).
TEST_P(CoSimulationCheckpoint, ARestoredBlockGoesOnExactly) {
  const auto archive = open(GetParam());
  const auto make = [&] { return std::make_unique<CoSimulationBlock>(archive, std::map<std::string, double>{{"step_distance", 1e-3}}, 0.0, 1.0, 1e-3); };
  const auto inputs = [](models::Block& b) {
    const int tacho = b.input_index("tacho_voltage"), angle = b.input_index("spindle_angle");
    return [=](double t, std::span<double> u) {
      u[tacho] = 2.0 * std::sin(2 * M_PI * 20 * t);
      u[angle] = 60.0 * t;
    };
  };
  auto block = make();
  solve::BlockIntegrator integrator(*block, {}, 0.0, {});
  const auto u = inputs(*block);
  integrator.advance_to(0.025, u);
  const std::vector<double> saved = block->save_discrete_state();
  std::vector<std::vector<double>> expected;
  std::vector<double> y(static_cast<std::size_t>(block->num_outputs()));
  for (int k = 26; k <= 60; ++k) {
    integrator.advance_to(k * 1e-3, u);
    block->calc_outputs(k * 1e-3, {}, {}, y);
    expected.push_back(y);
  }
  auto again = make();
  solve::BlockIntegrator restored(*again, {}, 0.0, {});
  restored.advance_to(0.0, u);
  restored.reset_state(0.025, {});
  again->restore_discrete_state(saved);
  for (int k = 26; k <= 60; ++k) {
    restored.advance_to(k * 1e-3, u);
    again->calc_outputs(k * 1e-3, {}, {}, y);
    ASSERT_EQ(y, expected[static_cast<std::size_t>(k - 26)]) << "t = " << k << " ms";
  }
}

INSTANTIATE_TEST_SUITE_P(TestFmus, CoSimulationCheckpoint,
                         ::testing::Values("servo_amplifier_fmi2_cs", "servo_amplifier_fmi3_cs"));

class TickerBlock : public ::testing::TestWithParam<const char*> {};

// The ticker (a counter stepped up by the FMU's time events every 10 ms, y integrating it):
// the model-exchange block lands on each time event, so count = floor(t / 10 ms) and
// y(t) = P n (n - 1) / 2 + n (t - n P). Advanced in steps of 5 ms, so that every second
// event is on a step's end (where it must not be missed or taken late) and the others
// inside. The events are located by CVODE's root finding on next_tick - t, never before
// the tick: 1e-9 s after it is asked (the root finder's resolution is ~1e-14 s here); y is
// piecewise linear, which CVODE integrates to round-off: 1e-9 s is asked, while an event
// landed a step late costs 5e-3 s.
TEST_P(TickerBlock, TimeEventsAreLandedOn) {
  const double period = 0.01;
  ModelExchangeBlock block(open(GetParam()), {{"period", period}}, 0.0, 1.0);
  ASSERT_EQ(block.num_inputs(), 0);
  ASSERT_EQ(block.num_event_functions(), 1);  // no indicators; the time-event function
  EXPECT_EQ(block.next_time_event(), period);
  std::vector<double> x(1);
  block.initial_state(0.0, x);
  solve::BlockIntegrator integrator(block, tight(), 0.0, x);
  std::vector<double> y(2);
  for (int k = 1; k <= 20; ++k) {
    const double t = k * 0.005;
    integrator.advance_to(t, {});
    block.calc_outputs(t, integrator.state(), {}, y);
    const double n = std::floor(t / period + 1e-9);
    EXPECT_EQ(y[static_cast<std::size_t>(block.output_index("count"))], n) << "t = " << t;
    EXPECT_NEAR(y[static_cast<std::size_t>(block.output_index("y"))],
                period * n * (n - 1) / 2 + n * (t - n * period), 1e-9)
        << "t = " << t;
  }
  const auto events = integrator.take_events();
  ASSERT_EQ(events.size(), 10u);
  for (std::size_t i = 0; i < events.size(); ++i) {
    const double tick = static_cast<double>(i + 1) * period;
    EXPECT_GE(events[i].t, tick - 1e-15 * tick) << "event " << i;
    EXPECT_LT(events[i].t, tick + 1e-9) << "event " << i;
  }
}

// Checkpointed at 25 ms (count 2, next tick 30 ms), run on to 60 ms; a new block restored
// from the checkpoint gives the same doubles. The counter is the FMU's discrete state, not
// a continuous one: a checkpoint of the continuous state alone would restart it at 0.
TEST_P(TickerBlock, ACheckpointHoldsTheDiscreteState) {
  const auto archive = open(GetParam());
  ModelExchangeBlock block(archive, {{"period", 0.01}}, 0.0, 1.0);
  std::vector<double> x(1);
  block.initial_state(0.0, x);
  solve::BlockIntegrator integrator(block, tight(), 0.0, x);
  integrator.advance_to(0.025, {});
  const std::vector<double> saved = block.save_discrete_state();
  const std::vector<double> saved_x(integrator.state().begin(), integrator.state().end());
  integrator.mark_discontinuity();  // as a node does at every macro step (and a restored one at its first)
  std::vector<double> y(2), expected(2);
  integrator.advance_to(0.06, {});
  block.calc_outputs(0.06, integrator.state(), {}, expected);
  EXPECT_EQ(expected[static_cast<std::size_t>(block.output_index("count"))], 6.0);

  ModelExchangeBlock again(archive, {{"period", 0.01}}, 0.0, 1.0);
  solve::BlockIntegrator restored(again, tight(), 0.0, x);
  restored.reset_state(0.025, saved_x);
  again.restore_discrete_state(saved);
  EXPECT_EQ(again.next_time_event(), 0.03);
  restored.advance_to(0.06, {});
  again.calc_outputs(0.06, restored.state(), {}, y);
  EXPECT_EQ(y, expected);

  ModelExchangeBlock continuous_only(archive, {{"period", 0.01}}, 0.0, 1.0);
  solve::BlockIntegrator without(continuous_only, tight(), 0.0, x);
  without.reset_state(0.025, saved_x);
  without.advance_to(0.06, {});
  continuous_only.calc_outputs(0.06, without.state(), {}, y);
  EXPECT_NE(y, expected);
}

INSTANTIATE_TEST_SUITE_P(TestFmus, TickerBlock, ::testing::Values("ticker_fmi2_me", "ticker_fmi3_me"));

// A model-exchange FMU with time events and no continuous states (tests/fmus/staircase):
// no integrator runs, the block integrator bisects on time for each time event and the
// FMU's discrete update runs there. Every 1 ms for 1 s (100 steps of the stair, every tenth
// macro instant on one), count and y against the closed form n(t) = floor(t / period),
// right-continuous: exact (the count is an integer; y = height n, one product), and the
// event found within the integrator's time resolution (1e-10 s) of its instant.
class StaircaseBlock : public ::testing::TestWithParam<const char*> {};

TEST_P(StaircaseBlock, RunsTheDiscreteUpdateAtEachEventTimeAsTheClosedForm) {
  constexpr double period = 0.01, height = 0.002;
  ModelExchangeBlock block(open(GetParam()), {{"period", period}, {"height", height}}, 0.0, 1.0);
  ASSERT_EQ(block.num_states(), 0);
  solve::BlockIntegrator integrator(block, tight(), 0.0, {});
  std::vector<double> y(2);
  const int count = block.output_index("count"), stair = block.output_index("y");
  for (int k = 0; k <= 1000; ++k) {
    const double t = k * 1e-3;
    integrator.advance_to(t, {});
    block.calc_outputs(t, {}, {}, y);
    const double n = std::floor(t / period + 1e-9);
    ASSERT_EQ(y[static_cast<std::size_t>(count)], n) << "t = " << t;
    ASSERT_EQ(y[static_cast<std::size_t>(stair)], height * n) << "t = " << t;
    EXPECT_NEAR(block.next_time_event(), (n + 1) * period, 1e-15) << "t = " << t;
  }
  const auto events = integrator.take_events();
  ASSERT_EQ(events.size(), 100u);
  for (std::size_t i = 0; i < events.size(); ++i) EXPECT_NEAR(events[i].t, (i + 1) * period, 1e-10) << "event " << i;
}

INSTANTIATE_TEST_SUITE_P(TestFmus, StaircaseBlock, ::testing::Values("staircase_fmi2_me", "staircase_fmi3_me"));

class TickerCoSimulation : public ::testing::TestWithParam<const char*> {};

// The co-simulation ticker: the FMU's own solver ends a substep on each time event. Stepped
// every 5 ms (every second tick on a step's end), y against the closed form: RK4 integrates
// a piecewise constant slope exactly, 1e-12 s is asked.
TEST_P(TickerCoSimulation, MatchesTheClosedForm) {
  CoSimulationBlock block(open(GetParam()), {{"period", 0.01}}, 0.0, 1.0, 0.005);
  solve::BlockIntegrator integrator(block, {}, 0.0, {});
  std::vector<double> y(2);
  for (int k = 0; k <= 20; ++k) {
    const double t = k * 0.005;
    integrator.advance_to(t, {});
    block.calc_outputs(t, {}, {}, y);
    const double n = std::floor(t / 0.01 + 1e-9);
    EXPECT_EQ(y[static_cast<std::size_t>(block.output_index("count"))], n) << "t = " << t;
    EXPECT_NEAR(y[static_cast<std::size_t>(block.output_index("y"))], 0.01 * n * (n - 1) / 2 + n * (t - n * 0.01), 1e-12)
        << "t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(TestFmus, TickerCoSimulation, ::testing::Values("ticker_fmi2_cs", "ticker_fmi3_cs"));

// --- <ModelStructure> dependencies as feedthrough ----------------------------------------

class Dependencies : public ::testing::TestWithParam<const char*> {};

// The servo amplifier FMU declares its outputs' dependencies; as a model-exchange block each
// output's direct feedthrough is then exactly the native continuous amplifier's (external
// setpoint, no current limit): the tacho voltage reaches no output directly (the law reads
// its filtered state). Before, every output was taken to depend on every input.
TEST_P(Dependencies, ServoAmplifierFeedthroughIsTheNativeOne) {
  ModelExchangeBlock fmu(open(std::string("servo_amplifier_") + GetParam() + "_me"), {}, 0.0, 1.0);
  models::nc::ServoAmplifierParams params;
  params.setpoint_source = models::nc::SetpointSource::external;
  models::nc::ServoAmplifierBlock native(params);
  const auto names = [](const models::Block& b, const std::vector<int>& inputs) {
    std::vector<std::string> out;
    for (int i : inputs) out.push_back(b.inputs()[static_cast<std::size_t>(i)].name);
    std::sort(out.begin(), out.end());
    return out;
  };
  for (const auto& port : native.outputs()) {
    const int o = fmu.output_index(port.name);
    ASSERT_GE(o, 0) << port.name;
    EXPECT_EQ(names(fmu, fmu.outputs()[static_cast<std::size_t>(o)].feedthrough), names(native, port.feedthrough))
        << port.name;
  }
}

// The lag's output is its state (dependencies: the state only): no feedthrough, so a loop
// through it is no algebraic loop.
TEST_P(Dependencies, LagHasNoFeedthrough) {
  ModelExchangeBlock lag(open(std::string("lag_") + GetParam() + "_me"), {}, 0.0, 1.0);
  ASSERT_EQ(lag.num_outputs(), 1);
  EXPECT_TRUE(lag.outputs()[0].feedthrough.empty());
}

INSTANTIATE_TEST_SUITE_P(TestFmus, Dependencies, ::testing::Values("fmi2", "fmi3"));

}  // namespace
}  // namespace mechsim::fmi
