// A scene whose servo amplifier is played by the servo amplifier FMU (`fmu:` under the
// participant): the plan builds the FMU's block in place of the native one, the monolithic
// reference and an in-process co-simulation run with it give the native loop's results, and
// what cannot work is refused with the scene's file and key before anything runs.
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include <gtest/gtest.h>

#include "fmu_files.h"
#include "in_process_run.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/composer.h"
#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/scene_plan.h"

namespace mechsim::fmi {
namespace {

using test::ScratchFolder;
using test::runs_in_process;
using test::test_fmu;

const std::string kScene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_slide_loop.yaml";

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// nc_slide_loop.yaml with `fmu_line` added to the servo participant, written into `folder`.
std::string scene_with_fmu(const ScratchFolder& folder, const std::string& fmu_line, const std::string& name) {
  std::string text = read_text(kScene);
  const std::string anchor = "    type: servo_amplifier\n";
  const auto at = text.find(anchor);
  if (at == std::string::npos) throw std::runtime_error("nc_slide_loop.yaml changed: no servo_amplifier line");
  text.insert(at + anchor.size(), "    " + fmu_line + "\n");
  const std::string path = folder.path(name).string();
  std::ofstream(path) << text;
  return path;
}

// The scene's amplifier parameters, given to the FMU with their units.
const std::string kParameters =
    "parameters: {position_gain: 40 1/s, velocity_gain: 10, integral_time: 10 ms, antiwindup_time: 5 ms, "
    "tacho_filter_time: 0.3 ms, voltage_limit: 50 V, step_distance: 0.1 mm}";

double worst_difference(const cosim::OutputLog& a, const cosim::OutputLog& b, std::string& where) {
  EXPECT_EQ(a.columns, b.columns);
  double worst = 0.0;
  for (std::size_t c = 1; c < std::min(a.columns.size(), b.columns.size()); ++c) {
    const auto& x = a.data[c];
    const auto& y = b.data[c];
    EXPECT_EQ(x.size(), y.size()) << a.columns[c];
    const double range = std::max(cosim::finite_range(x), 1e-12);
    for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
      if (std::abs(x[i] - y[i]) / range > worst) {
        worst = std::abs(x[i] - y[i]) / range;
        where = a.columns[c];
      }
  }
  return worst;
}

class FmuParticipant : public ::testing::TestWithParam<const char*> {
 protected:
  ScratchFolder scratch_;
};

// Model exchange: the FMU's law is the native one (bit-identical here, see
// nc_loop_fmu_test.cpp), so the reference and the in-process co-simulation run (three node
// threads, lock-step over the in-process transport) match the native scene's: measured
// bit-identical node logs; 1e-6 of each signal's range is asked (another compiler may
// contract the C law's operations differently).
TEST_P(FmuParticipant, ModelExchangeRunsLikeTheNativeAmplifier) {
  const std::string fmu = test_fmu(std::string(GetParam()) + "_me");
  const std::string path = scene_with_fmu(
      scratch_, "fmu: {file: " + fmu + ", interface: model-exchange, " + kParameters + "}", "fmu_me.yaml");
  const config::Scene scene = config::load_scene(path, {"time.end=0.02 s"});
  const config::Scene native_scene = config::load_scene(kScene, {"time.end=0.02 s"});

  cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  EXPECT_EQ(plan.node("servo").block->type_name(), "fmu");
  cosim::ScenePlan native_plan = cosim::ScenePlan::build(native_scene);
  std::string where;
  EXPECT_LT(worst_difference(cosim::run_reference(native_plan).log, cosim::run_reference(plan).log, where), 1e-6)
      << where;

  ASSERT_TRUE(runs_in_process(scene, scratch_.path("fmu_run")));
  ASSERT_TRUE(runs_in_process(native_scene, scratch_.path("native_run")));
  for (const char* node : {"servo", "tacho", "slide"}) {
    const std::string log = std::string(node) + ".outputs.bin";
    EXPECT_LT(worst_difference(cosim::read_output_log(scratch_.path("native_run/" + log).string()),
                               cosim::read_output_log(scratch_.path("fmu_run/" + log).string()), where),
              1e-6)
        << node << ": " << where;
  }
}

// Co-simulation every 1 ms against the native amplifier sampled every 1 ms, in process: the
// amplifier's two states are integrated by the FMU's RK4 (1 µs substeps) instead of the
// node's CVODE, which is therefore set to rtol 1e-10 here (at the scene's default 1e-6 its
// own error shows: 1.6e-5 of range apart). Measured 3.6e-9 of range; 1e-6 is asked.
TEST_P(FmuParticipant, CoSimulationRunsLikeTheNativeSampledAmplifier) {
  const std::string fmu = test_fmu(std::string(GetParam()) + "_cs");
  const std::string path = scene_with_fmu(
      scratch_, "fmu: {file: " + fmu + ", interface: co-simulation, step: 1 ms, " + kParameters + "}", "fmu_cs.yaml");
  const config::Scene scene = config::load_scene(path, {"time.end=0.02 s"});
  const config::Scene native_scene =
      config::load_scene(kScene, {"time.end=0.02 s", "participants.servo.params.sample_time=1 ms",
                                  "participants.servo.solver.rtol=1e-10", "participants.servo.solver.atol=1e-12"});
  ASSERT_TRUE(runs_in_process(scene, scratch_.path("fmu_run")));
  ASSERT_TRUE(runs_in_process(native_scene, scratch_.path("native_run")));
  std::string where;
  for (const char* node : {"servo", "tacho", "slide"}) {
    const std::string log = std::string(node) + ".outputs.bin";
    EXPECT_LT(worst_difference(cosim::read_output_log(scratch_.path("native_run/" + log).string()),
                               cosim::read_output_log(scratch_.path("fmu_run/" + log).string()), where),
              1e-6)
        << node << ": " << where;
  }
}

// The adaptive macro step with the model-exchange FMU as the amplifier, in process: no
// step is redone (the controller only shortens the next one), so the FMU's state is never
// put back, and the FMU declares the native amplifier's feedthrough (the coupling-error
// estimate reads it): the run takes the native scene's instants and gives its values.
// Measured bit-identical node logs; 1e-6 of each signal's range is asked, as above.
TEST_P(FmuParticipant, AdaptiveStepRunsLikeTheNativeAmplifier) {
  const std::string fmu = test_fmu(std::string(GetParam()) + "_me");
  const std::string path = scene_with_fmu(
      scratch_, "fmu: {file: " + fmu + ", interface: model-exchange, " + kParameters + "}", "fmu_adaptive.yaml");
  const std::vector<std::string> adaptive{"time.end=0.02 s", "time.step=adaptive", "time.tolerance=1e-4",
                                          "time.min=1 us", "time.max=100 us"};
  ASSERT_TRUE(runs_in_process(config::load_scene(path, adaptive), scratch_.path("fmu_run")));
  ASSERT_TRUE(runs_in_process(config::load_scene(kScene, adaptive), scratch_.path("native_run")));
  std::string where;
  for (const char* node : {"servo", "tacho", "slide"}) {
    const std::string log = std::string(node) + ".outputs.bin";
    const auto a = cosim::read_output_log(scratch_.path("native_run/" + log).string());
    const auto b = cosim::read_output_log(scratch_.path("fmu_run/" + log).string());
    ASSERT_EQ(a.data.at(0), b.data.at(0)) << node << ": the runs took different instants";
    EXPECT_GT(a.data.at(0).size(), 200u);  // adaptive: more than the 200 steps of max
    EXPECT_LT(worst_difference(a, b, where), 1e-6) << node << ": " << where;
  }
}

// The adaptive macro step with the co-simulation FMU (its own fixed step, 100 us): the
// adaptive grid lands on the FMU's sample instants as on a native sampled block's, so the
// FMU is always stepped by its fixed step and needs no variable communication step. Against
// the native amplifier sampled every 100 us (its CVODE at rtol 1e-10, as above), at the
// sample instants both runs land on. The two runs' other instants differ (2901 and 2910
// steps: the step controller sees the FMU's RK4 and CVODE differ by ~1e-9), so each carries
// its own coupling error, some 1e-3 of range at tolerance 1e-4 (docs/accuracy.md): measured
// 9.4e-4 of range apart (slide.coupling_torque), 8e-5 on the voltage; 3e-3 is asked, while
// a 1 % error in a gain of the law moves the voltage by 9e-3 of its range.
TEST_P(FmuParticipant, AdaptiveStepWithACoSimulationFmu) {
  const std::string fmu = test_fmu(std::string(GetParam()) + "_cs");
  const std::string path = scene_with_fmu(
      scratch_, "fmu: {file: " + fmu + ", interface: co-simulation, step: 100 us, " + kParameters + "}", "cs_adaptive.yaml");
  const std::vector<std::string> adaptive{"time.end=0.02 s", "time.step=adaptive", "time.tolerance=1e-4",
                                          "time.min=1 us", "time.max=100 us"};
  std::vector<std::string> native_settings = adaptive;
  for (const char* s : {"participants.servo.params.sample_time=100 us", "participants.servo.solver.rtol=1e-10",
                        "participants.servo.solver.atol=1e-12"})
    native_settings.emplace_back(s);
  ASSERT_TRUE(runs_in_process(config::load_scene(path, adaptive), scratch_.path("fmu_run")));
  ASSERT_TRUE(runs_in_process(config::load_scene(kScene, native_settings), scratch_.path("native_run")));
  std::string where;
  for (const char* node : {"servo", "tacho", "slide"}) {
    const std::string log = std::string(node) + ".outputs.bin";
    const auto a = cosim::read_output_log(scratch_.path("native_run/" + log).string());
    const auto b = cosim::read_output_log(scratch_.path("fmu_run/" + log).string());
    // The FMU's sample instants k * 100 us are in both runs' grids (landed on): compared there.
    const auto row_at = [](const cosim::OutputLog& log, double t) -> std::optional<std::size_t> {
      const auto& times = log.data[0];
      const auto it = std::lower_bound(times.begin(), times.end(), t - 1e-12);
      if (it == times.end() || std::abs(*it - t) > 1e-12) return std::nullopt;
      return static_cast<std::size_t>(it - times.begin());
    };
    double worst = 0.0;
    for (int k = 0; k <= 200; ++k) {
      const auto i = row_at(a, k * 1e-4), j = row_at(b, k * 1e-4);
      ASSERT_TRUE(i && j) << node << ": no step ends at the FMU's sample instant " << k * 1e-4 << " s";
      for (std::size_t c = 1; c < a.columns.size(); ++c) {
        const double range = std::max(cosim::finite_range(a.data[c]), 1e-12);
        if (std::abs(a.data[c][*i] - b.data[c][*j]) / range > worst) {
          worst = std::abs(a.data[c][*i] - b.data[c][*j]) / range;
          where = a.columns[c];
        }
      }
    }
    std::cout << node << ": " << a.data[0].size() << " / " << b.data[0].size() << " steps, worst difference " << worst
              << " of range (" << where << ")" << std::endl;
    EXPECT_LT(worst, 3e-3) << node << ": " << where;
  }
}

INSTANTIATE_TEST_SUITE_P(TestFmus, FmuParticipant, ::testing::Values("servo_amplifier_fmi2", "servo_amplifier_fmi3"));

// Refused while the plan is built, naming the scene file, the key and what was expected.
class FmuParticipantRefusals : public ::testing::Test {
 protected:
  std::string refusal(const std::string& fmu_line) {
    const std::string path = scene_with_fmu(scratch_, fmu_line, "refused.yaml");
    try {
      const config::Scene scene = config::load_scene(path);
      cosim::ScenePlan::build(scene);
    } catch (const config::ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      return what;
    }
    return "(not refused)";
  }
  ScratchFolder scratch_;
};

TEST_F(FmuParticipantRefusals, MissingFile) {
  const std::string what = refusal("fmu: {file: absent.fmu}");
  EXPECT_NE(what.find("participants.servo.fmu.file"), std::string::npos) << what;
  EXPECT_NE(what.find("(participant 'servo'): no such file"), std::string::npos) << what;
}

TEST_F(FmuParticipantRefusals, InterfaceNotOffered) {
  const std::string what = refusal("fmu: {file: " + test_fmu("servo_amplifier_fmi3_me") + ", interface: co-simulation}");
  EXPECT_NE(what.find("does not offer the co-simulation interface (it offers model-exchange)"), std::string::npos)
      << what;
}

TEST_F(FmuParticipantRefusals, FmuWithoutTheNativePorts) {
  const std::string what = refusal("fmu: {file: " + test_fmu("lag_fmi2_cs") + "}");
  EXPECT_NE(what.find("expected the FMU to have an output 'armature_voltage'"), std::string::npos) << what;
}

TEST_F(FmuParticipantRefusals, UnknownParameter) {
  const std::string what =
      refusal("fmu: {file: " + test_fmu("servo_amplifier_fmi2_cs") + ", parameters: {k_p: 40 1/s}}");
  EXPECT_NE(what.find("participants.servo.fmu.parameters.k_p"), std::string::npos) << what;
  EXPECT_NE(what.find("expected a parameter of the FMU"), std::string::npos) << what;
}

TEST_F(FmuParticipantRefusals, ParameterInTheWrongDimension) {
  const std::string what =
      refusal("fmu: {file: " + test_fmu("servo_amplifier_fmi2_cs") + ", parameters: {integral_time: 10 mm}}");
  EXPECT_NE(what.find("participants.servo.fmu.parameters.integral_time"), std::string::npos) << what;
}

TEST_F(FmuParticipantRefusals, UnitDifferentFromTheNativePort) {
  // The servo amplifier FMU with its tacho voltage input declared in rad.
  std::vector<std::pair<std::string, std::string>> entries;
  for (auto [name, content] : test::read_zip(test_fmu("servo_amplifier_fmi3_cs"))) {
    if (name == "modelDescription.xml") {
      const std::string from = R"(name="tacho_voltage" valueReference="0" causality="input" variability="continuous" unit="V")";
      const auto at = content.find(from);
      ASSERT_NE(at, std::string::npos);
      content.replace(at, from.size(), R"(name="tacho_voltage" valueReference="0" causality="input" variability="continuous" unit="rad")");
    }
    entries.emplace_back(name, content);
  }
  const std::string fmu = scratch_.path("rad_tacho.fmu").string();
  test::write_zip(fmu, entries);
  const std::string what = refusal("fmu: {file: rad_tacho.fmu}");  // relative to the scene file
  EXPECT_NE(what.find("expected FMU input 'tacho_voltage' in the native port's unit 'V', got 'rad'"),
            std::string::npos)
      << what;
}

// A rollback restores every node's checkpoint: an FMU that cannot save its state (the lag
// declares neither flag) is refused when any participant may restart, naming the key that
// asks for it and the missing flags; the servo amplifier FMU, which declares both, is not.
TEST_F(FmuParticipantRefusals, RestartNeedsAnFmuThatSavesItsState) {
  const std::string lag = "fmu: {file: " + test_fmu("lag_fmi2_cs") + "}";
  std::string what = refusal(lag + "\n    restart: on_failure");
  EXPECT_NE(what.find("participants.servo.restart: expected restart: never while participant 'servo' is played by an "
                      "FMU that cannot save its state"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("does not declare canGetAndSetFMUstate and canSerializeFMUstate (its co-simulation interface)"),
            std::string::npos)
      << what;
  // Another participant's restart rolls the FMU back as well.
  const std::string path = scene_with_fmu(scratch_, "fmu: {file: " + test_fmu("lag_fmi3_me") + ", interface: model-exchange}",
                                          "other.yaml");
  try {
    cosim::ScenePlan::build(config::load_scene(path, {"participants.slide.restart=on_failure"}));
    ADD_FAILURE() << "not refused";
  } catch (const config::ConfigError& e) {
    what = e.what();
    EXPECT_NE(what.find("participants.slide.restart: expected restart: never"), std::string::npos) << what;
    EXPECT_NE(what.find("canGetAndSetFMUState and canSerializeFMUState (its model-exchange interface)"), std::string::npos)
        << what;
  }
  for (const char* servo : {"servo_amplifier_fmi2_cs", "servo_amplifier_fmi3_me"}) {
    const std::string ok = scene_with_fmu(scratch_, "fmu: {file: " + test_fmu(servo) + ", interface: " +
                                                        (std::string(servo).ends_with("_me") ? "model-exchange" : "co-simulation") +
                                                        ", " + kParameters + "}",
                                          "ok.yaml");
    EXPECT_NO_THROW(cosim::ScenePlan::build(config::load_scene(ok, {"faults.restart=on_failure"}))) << servo;
  }
}

TEST_F(FmuParticipantRefusals, UnknownKey) {
  const std::string what = refusal("fmu: {file: x.fmu, version: 2}");
  EXPECT_NE(what.find("version"), std::string::npos) << what;
}

}  // namespace
}  // namespace mechsim::fmi
