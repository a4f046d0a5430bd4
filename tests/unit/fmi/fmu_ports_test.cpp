// Participants of type fmu with ports of their own (docs/fmi.md, "FMU participants"):
// what the plan makes of them (topic, topic type, port-level edges), what it refuses
// (units, unknown ports, a participant-level connection), and the NC slide loop with the
// servo amplifier FMU joined port by port to the native tachometer and slide, in process.
#include <fstream>
#include <functional>
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

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
}

void replace_once(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("scene changed: no '" + from + "'");
  text.replace(at, from.size(), to);
}

class FmuPorts : public ::testing::Test {
 protected:
  // config/scenes/fmu_speed_lag.yaml with this build's FMUs and `edit` applied.
  std::string speed_lag_scene(const std::function<void(std::string&)>& edit = {}) {
    std::string text = read_text(std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/fmu_speed_lag.yaml");
    replace_all(text, "../../build/tests/fmus/speed_lag_fmi2_cs.fmu", test_fmu("speed_lag_fmi2_cs"));
    replace_all(text, "../../build/tests/fmus/speed_lag_fmi3_me.fmu", test_fmu("speed_lag_fmi3_me"));
    if (edit) edit(text);
    const std::string path = scratch_.path("scene" + std::to_string(++scenes_) + ".yaml").string();
    std::ofstream(path) << text;
    return path;
  }
  std::string refusal(const std::string& path) {
    const config::Scene scene = config::load_scene(path);
    try {
      cosim::ScenePlan::build(scene);
    } catch (const config::ConfigError& e) {
      return e.what();
    }
    return "(not refused)";
  }
  ScratchFolder scratch_;
  int scenes_ = 0;
};

TEST_F(FmuPorts, TheFmusOutputsAreTheirTopicsFields) {
  const config::Scene scene = config::load_scene(speed_lag_scene());
  const cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  const cosim::PlannedNode& lag = plan.node("lag");
  EXPECT_EQ(lag.topic, "lag/outputs");
  EXPECT_EQ(lag.type->name, "fmu");
  EXPECT_EQ(lag.type->publishes->idl_name, "mechsim::msg::FmuOutputs");
  EXPECT_EQ(lag.type->publishes->layout, transport::TopicLayout::sequences);
  ASSERT_EQ(lag.type->publishes->fields.size(), 1u);
  EXPECT_EQ(lag.type->publishes->fields[0].name, "y");
  EXPECT_EQ(lag.type->publishes->fields[0].unit, "rad/s");
  EXPECT_TRUE(lag.steps_itself);
  EXPECT_FALSE(plan.node("filter").steps_itself);
  // cam.speed feeds lag.u through one edge of the cam's topic.
  ASSERT_EQ(lag.inputs.size(), 1u);
  EXPECT_EQ(lag.inputs[0].topic, "cam/state");
  ASSERT_EQ(lag.inputs[0].field_to_input.size(), 1u);
  EXPECT_EQ(lag.inputs[0].field_to_input[0].first, transport::find_topic_type("CamState")->field_index("speed"));
  EXPECT_EQ(lag.inputs[0].field_to_input[0].second, lag.block->input_index("u"));
  EXPECT_EQ(plan.node("cam").subscriber_count, 2);
}

TEST_F(FmuPorts, UnitsThatDifferAreRefusedNamingBoth) {
  const std::string path = speed_lag_scene([](std::string& t) { replace_once(t, "from: cam.speed, to: lag.u", "from: cam.angle, to: lag.u"); });
  const std::string why = refusal(path);
  EXPECT_NE(why.find(path + ": connections[0]"), std::string::npos) << why;
  EXPECT_NE(why.find("cam.angle is in 'rad', lag.u in 'rad/s'"), std::string::npos) << why;
}

TEST_F(FmuPorts, UnknownPortsAreRefusedWithThePortsThereAre) {
  std::string why = refusal(speed_lag_scene([](std::string& t) { replace_once(t, "to: lag.u", "to: lag.v"); }));
  EXPECT_NE(why.find("connections[0].to"), std::string::npos) << why;
  EXPECT_NE(why.find("expected an input of 'lag' (u), got 'v'"), std::string::npos) << why;
  why = refusal(speed_lag_scene([](std::string& t) {
    replace_once(t, "{from: cam.speed, to: filter.u, order: gauss_seidel}", "{from: lag.yy, to: filter.u}");
  }));
  EXPECT_NE(why.find("expected an output 'lag' publishes (y), got 'yy'"), std::string::npos) << why;
}

TEST_F(FmuPorts, AParticipantLevelConnectionToAnFmuIsRefused) {
  const std::string why = refusal(speed_lag_scene([](std::string& t) {
    replace_once(t, "{from: cam.speed, to: lag.u, order: gauss_seidel}", "{from: cam, to: lag}");
  }));
  EXPECT_NE(why.find("expected a port-level connection (from: cam.OUTPUT, to: lag.INPUT)"), std::string::npos) << why;
}

TEST_F(FmuPorts, HalfAPortLevelConnectionIsRefused) {
  const std::string path = speed_lag_scene([](std::string& t) { replace_once(t, "from: cam.speed, to: lag.u", "from: cam, to: lag.u"); });
  try {
    config::load_scene(path);
    FAIL() << "not refused";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("connections[0].from"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("participant.port on both sides"), std::string::npos) << e.what();
  }
}

// An FMU's output feeds another FMU (FmuOutputs read by an FMU participant): the lag's y
// drives a second model-exchange lag. In process, against the monolithic reference, whose
// lag steps itself inside it and holds y(t_k) over each step, as the Jacobi edge with hold
// does in the run: the two differ by the integrators only.
TEST_F(FmuPorts, AnFmuFeedsAnotherFmuInProcess) {
  const std::string path = speed_lag_scene([](std::string& t) {
    replace_once(t, "compare: [lag.y, filter.y]", "");
    replace_once(t, "connections:\n", "  second:\n    type: fmu\n    fmu: " + test_fmu("speed_lag_fmi2_me") +
                                          "\n    interface: model-exchange\n    parameters: {k: 1, T: 20 ms}\n"
                                          "    solver: {rtol: 1e-10, atol: 1e-12}\n\nconnections:\n"
                                          "  - {from: lag.y, to: second.u, order: jacobi, reconstruction: hold}\n");
    t += "compare: [lag.y, filter.y, second.y]\n";
  });
  const config::Scene scene = config::load_scene(path);
  std::filesystem::create_directories(scratch_.path("run"));
  const auto run = cosim::run_inproc(scene, {.run_dir = scratch_.path("run").string()});
  ASSERT_TRUE(run.ok) << run.reason;
  cosim::ScenePlan plan = cosim::ScenePlan::build(scene);
  const cosim::ReferenceRun ref = cosim::run_reference(plan);
  const cosim::OutputLog second = cosim::read_output_log(scratch_.path("run/second.outputs.bin").string());
  const int y = second.column("y"), ry = ref.log.column("second.y");
  ASSERT_GE(y, 0);
  ASSERT_GE(ry, 0);
  ASSERT_EQ(second.rows(), ref.log.rows());
  double worst = 0.0, top = 0.0;
  for (std::size_t r = 0; r < second.rows(); ++r) {
    worst = std::max(worst, std::abs(second.data[y][r] - ref.log.data[ry][r]));
    top = std::max(top, std::abs(ref.log.data[ry][r]));
  }
  // y2 rises towards k2 k1 w = 6.3 rad/s; both integrate the same held input with CVODE
  // at rtol 1e-10: 1e-6 of the top value allows for the solvers' different step choices.
  EXPECT_GT(top, 5.0);
  EXPECT_LT(worst, 1e-6 * top);
}

// The NC slide loop with its amplifier as a type: fmu participant whose ports are joined
// one by one to the native tachometer and slide (native -> FMU and FMU -> native), against
// the native scene: the FMU's law is the native one (docs/fmi.md), so the node logs of the
// tachometer and the slide agree to 1e-6 of each signal's range (bit-identical measured
// with the FMU in place of the native block).
TEST_F(FmuPorts, TheNcLoopWithAnAmplifierFmuJoinedPortByPort) {
  std::string text = read_text(std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_slide_loop.yaml");
  const auto from = text.find("  servo:\n"), to = text.find("  tacho:\n");
  ASSERT_NE(from, std::string::npos);
  text.replace(from, to - from,
               "  servo:\n    type: fmu\n    fmu: " + test_fmu("servo_amplifier_fmi2_me") +
                   "\n    interface: model-exchange\n"
                   "    parameters: {position_gain: 40 1/s, velocity_gain: 10, integral_time: 10 ms, antiwindup_time: 5 ms,\n"
                   "                 tacho_filter_time: 0.3 ms, voltage_limit: 50 V, step_distance: 0.1 mm}\n");
  replace_once(text, "{from: servo, to: tacho,", "{from: servo.armature_voltage, to: tacho.armature_voltage,");
  replace_once(text, "{from: tacho, to: servo,", "{from: tacho.tacho_voltage, to: servo.tacho_voltage,");
  replace_once(text, "{from: slide, to: servo,", "{from: slide.spindle_angle, to: servo.spindle_angle,");
  const std::string path = scratch_.path("nc_ports.yaml").string();
  std::ofstream(path) << text;
  const config::Scene scene = config::load_scene(path, {"time.end=0.02 s"});
  const config::Scene native_scene =
      config::load_scene(std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_slide_loop.yaml", {"time.end=0.02 s"});
  ASSERT_TRUE(runs_in_process(scene, scratch_.path("fmu_run")));
  ASSERT_TRUE(runs_in_process(native_scene, scratch_.path("native_run")));
  for (const char* node : {"tacho", "slide"}) {
    const std::string log = std::string(node) + ".outputs.bin";
    const cosim::OutputLog a = cosim::read_output_log(scratch_.path("native_run/" + log).string());
    const cosim::OutputLog b = cosim::read_output_log(scratch_.path("fmu_run/" + log).string());
    ASSERT_EQ(a.columns, b.columns);
    for (std::size_t c = 1; c < a.columns.size(); ++c) {
      const double range = std::max(cosim::finite_range(a.data[c]), 1e-12);
      ASSERT_EQ(a.data[c].size(), b.data[c].size());
      for (std::size_t r = 0; r < a.data[c].size(); ++r)
        ASSERT_LT(std::abs(a.data[c][r] - b.data[c][r]) / range, 1e-6) << node << "." << a.columns[c] << " row " << r;
    }
  }
}

}  // namespace
}  // namespace mechsim::fmi
