// The servo amplifier FMU in place of the native amplifier in the NC slide loop
// (config/scenes/nc_slide_loop.yaml: amplifier | motor + tacho | spindle + slide, a 0.1 mm
// step), integrated as one ODE by the monolithic composer (cosim::run_reference): the loop
// with the FMU matches the native loop. Model Exchange: the FMU's states join the composite
// ODE; Co-Simulation: the FMU steps itself as a sampled block, against the native amplifier
// in its sampled mode.
//
// The FMU is put into a plan built from the scene by swapping the amplifier's block: its
// ports are checked by name and index against the native block's first, so the plan's wires
// (made for the native block) reach the same variables. (A scene cannot name an FMU yet.)
#include <cmath>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/fmi/co_simulation_block.h"
#include "mechsim/fmi/model_exchange_block.h"
#include "mechsim/models/nc/servo_amplifier_block.h"

namespace mechsim::fmi {
namespace {

using test::test_fmu;

const std::string kScene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_slide_loop.yaml";

// The FMU parameters of the native amplifier's, after checking that the FMU can express them.
std::map<std::string, double> fmu_parameters(const models::nc::ServoAmplifierParams& p) {
  EXPECT_EQ(p.setpoint_source, models::nc::SetpointSource::internal);
  EXPECT_EQ(p.setpoint.kind, models::nc::SetpointKind::step);
  EXPECT_EQ(p.setpoint.start_time, 0.0);
  EXPECT_FALSE(p.current_limit.enabled);
  EXPECT_EQ(p.velocity_feedforward, 0.0);
  EXPECT_FALSE(p.measure_on_motor);
  return {{"position_gain", p.position_gain},         {"velocity_gain", p.velocity_gain},
          {"integral_time", p.integral_time},         {"antiwindup_time", p.antiwindup_time},
          {"tacho_filter_time", p.tacho_filter_time}, {"voltage_limit", p.voltage_limit},
          {"tacho_constant", p.tacho_constant},       {"lead", p.lead},
          {"step_distance", p.setpoint.distance}};
}

// Replaces the plan's `servo` block by `fmu` after checking that every port of the native
// block is the FMU's port of the same name and index (the FMU may have more inputs; they
// stay at their start values).
void swap_in(cosim::ScenePlan& plan, std::unique_ptr<models::Block> fmu) {
  auto& node = plan.node("servo");
  const models::Block& native = *node.block;
  for (int i = 0; i < native.num_inputs(); ++i)
    ASSERT_EQ(fmu->input_index(native.inputs()[static_cast<std::size_t>(i)].name), i);
  ASSERT_EQ(fmu->num_outputs(), native.num_outputs());
  for (int i = 0; i < native.num_outputs(); ++i)
    ASSERT_EQ(fmu->output_index(native.outputs()[static_cast<std::size_t>(i)].name), i);
  node.block = std::move(fmu);
}

// Max |a - b| of every column, relative to the column's range in `a` (at least 1e-12).
double worst_relative_difference(const cosim::OutputLog& a, const cosim::OutputLog& b, std::string& where) {
  double worst = 0.0;
  EXPECT_EQ(a.columns, b.columns);
  for (std::size_t c = 0; c < a.columns.size() && c < b.columns.size(); ++c) {
    const std::string& column = a.columns[c];
    if (column == "t") continue;
    const auto& x = a.data[c];
    const auto& y = b.data[c];
    EXPECT_EQ(x.size(), y.size()) << column;
    double lo = x.front(), hi = x.front(), diff = 0.0;
    for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
      lo = std::min(lo, x[i]);
      hi = std::max(hi, x[i]);
      diff = std::max(diff, std::abs(x[i] - y[i]));
    }
    const double relative = diff / std::max(hi - lo, 1e-12);
    if (relative > worst) {
      worst = relative;
      where = column;
    }
  }
  return worst;
}

class NcLoopWithFmu : public ::testing::TestWithParam<const char*> {};

// Model Exchange: the composite ODE is the same system (the same law, in C instead of C++),
// integrated by CVODE at the reference's rtol 1e-10 / atol 1e-12. Measured here: identical
// to the last bit (the C law does the native C++ law's operations in the same order, and
// x86-64 without -march has no fused multiply-add to reorder them). A different compiler or
// flags may contract differently; the integrator then follows a round-off apart path, still
// far inside 1e-6 of each signal's range, which is asked. A 1 % error in one gain moves the
// loop by 0.9 % of the armature voltage's range (tried).
TEST_P(NcLoopWithFmu, ModelExchangeMatchesTheNativeLoop) {
  const config::Scene scene = config::load_scene(kScene, {"time.end=0.05 s"});
  cosim::ScenePlan native_plan = cosim::ScenePlan::build(scene);
  const cosim::ReferenceRun native = cosim::run_reference(native_plan);

  cosim::ScenePlan fmu_plan = cosim::ScenePlan::build(scene);
  const auto& amplifier = dynamic_cast<const models::nc::ServoAmplifierBlock&>(*fmu_plan.node("servo").block);
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{test_fmu(std::string(GetParam()) + "_me"), "servo"});
  swap_in(fmu_plan, std::make_unique<ModelExchangeBlock>(archive, fmu_parameters(amplifier.params()), 0.0, 0.05));
  const cosim::ReferenceRun with_fmu = cosim::run_reference(fmu_plan);

  std::string where;
  EXPECT_LT(worst_relative_difference(native.log, with_fmu.log, where), 1e-6) << where;
  // The step was taken: the slide moved most of the 0.1 mm by 50 ms.
  const int position = native.log.column("slide.slide_position");
  ASSERT_GE(position, 0);
  EXPECT_GT(native.log.data[static_cast<std::size_t>(position)].back(), 0.5e-4);
}

// Co-Simulation: the amplifier samples every 1 ms (sample_time set on the native one) and
// the FMU steps itself on that grid; the rest of the loop is integrated by CVODE as before.
// The FMU's RK4 (1 µs substeps) and CVODE integrate the amplifier's two states between
// samples; measured: 1.8e-7 of the coupling torque's range apart, the largest; 1e-5 is asked.
TEST_P(NcLoopWithFmu, CoSimulationMatchesTheNativeSampledLoop) {
  const config::Scene scene = config::load_scene(kScene, {"time.end=0.05 s", "participants.servo.params.sample_time=1 ms"});
  cosim::ScenePlan native_plan = cosim::ScenePlan::build(scene);
  const cosim::ReferenceRun native = cosim::run_reference(native_plan);

  cosim::ScenePlan fmu_plan = cosim::ScenePlan::build(scene);
  const auto& amplifier = dynamic_cast<const models::nc::ServoAmplifierBlock&>(*fmu_plan.node("servo").block);
  ASSERT_EQ(amplifier.params().sample_time, 1e-3);
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{test_fmu(std::string(GetParam()) + "_cs"), "servo"});
  swap_in(fmu_plan,
          std::make_unique<CoSimulationBlock>(archive, fmu_parameters(amplifier.params()), 0.0, 0.05, 1e-3));
  const cosim::ReferenceRun with_fmu = cosim::run_reference(fmu_plan);

  std::string where;
  EXPECT_LT(worst_relative_difference(native.log, with_fmu.log, where), 1e-5) << where;
}

INSTANTIATE_TEST_SUITE_P(TestFmus, NcLoopWithFmu, ::testing::Values("servo_amplifier_fmi2", "servo_amplifier_fmi3"));

}  // namespace
}  // namespace mechsim::fmi
