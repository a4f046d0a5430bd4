// Co-Simulation FMUs as sampled blocks driven by solve::BlockIntegrator: the lag against its
// closed form, the servo amplifier against the native sampled ServoAmplifierBlock.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "mechsim/fmi/co_simulation_block.h"
#include "mechsim/models/nc/servo_amplifier_block.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::fmi {
namespace {

using test::test_fmu;

class LagCoSimulationBlock : public ::testing::TestWithParam<const char*> {};

// k = 2, T = 0.05 s, y0 = 0.5 V, u = 1 V, Ts = 1 ms: the output held from t_k is y(t_k) of
// the closed form (the input is constant, so holding it loses nothing); the FMU's RK4
// substeps keep it to round-off (see instance_test.cpp): 1e-10 V.
TEST_P(LagCoSimulationBlock, HeldOutputsFollowTheClosedForm) {
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{test_fmu(GetParam()), "lag"});
  CoSimulationBlock block(archive, {{"k", 2.0}, {"T", 0.05}, {"y0", 0.5}}, 0.0, 1.0, 1e-3);
  ASSERT_EQ(block.num_states(), 0);
  EXPECT_EQ(block.sample_time(), 1e-3);
  EXPECT_TRUE(block.outputs()[0].feedthrough.empty());
  solve::BlockIntegrator integrator(block, {}, 0.0, {});
  const auto input = [](double, std::span<double> u) { u[0] = 1.0; };
  double worst = 0.0;
  for (int n = 0; n <= 200; ++n) {
    const double t = n * 1e-3;
    integrator.advance_to(t, input);
    double y = 0.0;
    block.calc_outputs(t, {}, {}, {&y, 1});
    worst = std::max(worst, std::abs(y - (2.0 - 1.5 * std::exp(-t / 0.05))));
  }
  EXPECT_LT(worst, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(TestFmus, LagCoSimulationBlock, ::testing::Values("lag_fmi2_cs", "lag_fmi3_cs"));

class ServoAmplifierCoSimulation : public ::testing::TestWithParam<const char*> {};

// The servo amplifier FMU as a co-simulation block against the native amplifier in its
// sampled mode (sample_time = Ts = 1 ms, external setpoint): both sample the inputs at t_k,
// hold U_a(t_k) and integrate z and U_Tf with the held inputs in between. Inputs: a 1 mm
// setpoint step (the voltage saturates at 50 V, so the anti-windup acts), a spindle turning
// at 60 rad/s and a tacho voltage oscillating at 20 Hz. The native block is integrated by
// CVODE at rtol 1e-10, the FMU by RK4 with 1 µs substeps (h/τ_f = 1/300: local error
// ~1e-13 relative); measured 1.2e-8 V apart, 1e-6 V on outputs of up to 50 V is asked, while
// sampling at the wrong instant or holding the wrong input moves U_a by volts.
TEST_P(ServoAmplifierCoSimulation, MatchesTheNativeSampledAmplifier) {
  const double ts = 1e-3;
  models::nc::ServoAmplifierParams params;
  params.setpoint_source = models::nc::SetpointSource::external;
  params.sample_time = ts;
  models::nc::ServoAmplifierBlock native(params);
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{test_fmu(GetParam()), "amp"});
  CoSimulationBlock fmu(archive, {}, 0.0, 1.0, ts);
  ASSERT_EQ(fmu.num_inputs(), 3);
  for (const char* name : {"tacho_voltage", "spindle_angle", "position_setpoint"})
    ASSERT_GE(fmu.input_index(name), 0) << name;

  const auto inputs_for = [](const models::Block& b) {
    const int tacho = b.input_index("tacho_voltage"), angle = b.input_index("spindle_angle"),
              setpoint = b.input_index("position_setpoint");
    return [=](double t, std::span<double> u) {
      u[tacho] = 2.0 * std::sin(2 * std::numbers::pi * 20 * t);
      u[angle] = 60.0 * t;
      u[setpoint] = 1e-3;
    };
  };
  solve::SolverOptions tight;
  tight.rtol = 1e-10;
  tight.atol = 1e-12;
  std::vector<double> x0(2, 0.0);
  solve::BlockIntegrator native_integrator(native, tight, 0.0, x0);
  solve::BlockIntegrator fmu_integrator(fmu, tight, 0.0, {});
  const auto native_inputs = inputs_for(native);
  const auto fmu_inputs = inputs_for(fmu);
  std::vector<double> native_y(static_cast<std::size_t>(native.num_outputs()));
  std::vector<double> fmu_y(static_cast<std::size_t>(fmu.num_outputs()));
  std::vector<double> native_u(3), fmu_u(3);
  double worst = 0.0;
  int saturated_samples = 0;
  for (int n = 0; n <= 60; ++n) {
    const double t = n * ts;
    native_integrator.advance_to(t, native_inputs);
    fmu_integrator.advance_to(t, fmu_inputs);
    native_inputs(t, native_u);
    fmu_inputs(t, fmu_u);
    native.calc_outputs(t, native_integrator.state(), native_u, native_y);
    fmu.calc_outputs(t, {}, fmu_u, fmu_y);
    for (const char* out : {"armature_voltage", "velocity_error", "following_error", "position_reference"})
      worst = std::max(worst, std::abs(fmu_y[fmu.output_index(out)] - native_y[native.output_index(out)]));
    EXPECT_EQ(fmu_y[fmu.output_index("saturated")], native_y[native.output_index("saturated")]) << "t = " << t;
    saturated_samples += native_y[native.output_index("saturated")] == 1.0;
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(saturated_samples, 0);   // the clamp and the anti-windup were exercised
  EXPECT_LT(saturated_samples, 61);  // and so was the linear range
}

INSTANTIATE_TEST_SUITE_P(TestFmus, ServoAmplifierCoSimulation,
                         ::testing::Values("servo_amplifier_fmi2_cs", "servo_amplifier_fmi3_cs"));

TEST(CoSimulationBlock, StepErrorNamesFunctionAndTime) {
  const std::string file = test_fmu("faulty_fmi2_cs");
  const auto archive = std::make_shared<const FmuArchive>(FmuLabel{file, "bad"});
  CoSimulationBlock block(archive, {{"fault", 1}, {"fault_time", 0.25}}, 0.0, 1.0, 0.125);
  solve::BlockIntegrator integrator(block, {}, 0.0, {});
  integrator.advance_to(0.25, {});
  try {
    integrator.advance_to(0.5, {});
    ADD_FAILURE() << "not refused";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("FMU '" + file + "' (participant 'bad'): fmi2DoStep returned fmi2Error at t = 0.25 s"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace mechsim::fmi
