// `mechsim fmu export` round trip: participants of config/scenes/nc_slide_loop.yaml written
// as co-simulation FMUs (FMI 2 and 3), read back with the project's importer (libs/fmi:
// the archive, the description, `mechsim fmu info`, an FmuInstance driving the binary),
// and stepped against the native block integrated as a node integrates it.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <numbers>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <sys/wait.h>

#include <gtest/gtest.h>

#include "fmu_info.h"
#include "mechsim/config/scene.h"
#include "mechsim/catalog/catalog.h"
#include "mechsim/cosim/inproc_run.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/node_stepper.h"
#include "mechsim/fmi/archive.h"
#include "mechsim/fmi/fmi2_functions.h"
#include "mechsim/fmi/instance.h"
#include "mechsim/fmi_export/fmu_writer.h"
#include "mechsim/solve/block_integrator.h"

namespace mechsim::fmi_export {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/nc_slide_loop.yaml";

class Scratch {
 public:
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "mechsim-export-test-XXXXXX").string();
    folder_ = mkdtemp(pattern.data());
  }
  ~Scratch() { fs::remove_all(folder_); }
  std::string path(const std::string& name) const { return (fs::path(folder_) / name).string(); }

 private:
  std::string folder_;
};

// Exports a participant of the NC loop scene (with `overrides`) and returns its config.
ExportConfig export_participant(const config::Scene& scene, const std::string& type, const std::string& name,
                                int fmi_version, const std::string& file) {
  ExportRequest request{type, name, fmi_version, file, MECHSIM_FMU_BINARY};
  ExportConfig config = export_config(scene, request);
  write_fmu(config, request);
  return config;
}

const fmi::Variable& variable(const fmi::ModelDescription& d, const std::string& name) {
  for (const auto& v : d.variables)
    if (v.name == name) return v;
  throw std::runtime_error("no variable " + name);
}

struct Case {
  const char* type;
  const char* participant;
  int fmi;
  const char* scene = "nc_slide_loop.yaml";
};

class ExportedParticipantFmu : public ::testing::TestWithParam<Case> {};

// What the importer reads: FMI version, the co-simulation interface with the flags the
// binary has (any step length, FMU state get/set and serialized), the block's ports with their SI units, and the
// scene's parameters in SI with units from <UnitDefinitions>; `mechsim fmu info` lists them.
TEST(ExportedServoAmplifier, DescriptionListsPortsParametersUnitsAndTrueFlags) {
  const config::Scene scene = config::load_scene(kScene);
  for (const int fmi : {2, 3}) {
    Scratch scratch;
    const std::string file = scratch.path("servo.fmu");
    export_participant(scene, "servo_amplifier", "servo", fmi, file);
    const fmi::FmuArchive archive(fmi::FmuLabel{file, "servo"});
    const fmi::ModelDescription& d = archive.description();
    EXPECT_EQ(d.version, fmi == 2 ? fmi::FmiVersion::fmi2 : fmi::FmiVersion::fmi3);
    ASSERT_EQ(d.interfaces.size(), 1u);
    const fmi::Interface& cs = d.interfaces[0];
    EXPECT_EQ(cs.kind, fmi::InterfaceKind::co_simulation);
    EXPECT_EQ(cs.model_identifier, "servo");
    EXPECT_TRUE(cs.can_handle_variable_step);
    EXPECT_TRUE(cs.can_get_and_set_state);
    EXPECT_TRUE(cs.can_serialize_state);
    EXPECT_FALSE(cs.provides_directional_derivatives);
    EXPECT_EQ(variable(d, "tacho_voltage").causality, fmi::Causality::input);
    EXPECT_EQ(variable(d, "tacho_voltage").unit, "V");
    EXPECT_EQ(variable(d, "spindle_angle").unit, "rad");
    EXPECT_EQ(variable(d, "armature_voltage").causality, fmi::Causality::output);
    EXPECT_EQ(variable(d, "armature_voltage").unit, "V");
    const fmi::Variable& gain = variable(d, "position_gain");
    EXPECT_EQ(gain.causality, fmi::Causality::parameter);
    EXPECT_EQ(gain.unit, "1/s");
    EXPECT_EQ(std::stod(gain.start.value()), 40.0);
    EXPECT_EQ(variable(d, "integral_time").unit, "s");
    EXPECT_EQ(std::stod(variable(d, "integral_time").start.value()), 0.01);
    EXPECT_EQ(std::stod(variable(d, "setpoint.distance").start.value()), 1e-4);  // 0.1 mm in SI
    EXPECT_EQ(variable(d, "velocity_gain").unit, "");  // a bare number in the scene
    EXPECT_EQ(d.default_step_size.value_or(0.0), scene.time.step);  // 25 us, read back exactly
    EXPECT_EQ(d.default_stop_time.value_or(0.0), scene.time.end);
    const auto volt = std::find_if(d.units.begin(), d.units.end(), [](const auto& u) { return u.name == "V"; });
    ASSERT_NE(volt, d.units.end());
    const std::string info = tools::format_fmu_info(archive);
    EXPECT_NE(info.find("variable step yes, get/set state yes, serialize state yes"), std::string::npos) << info;
    EXPECT_NE(info.find("position_gain"), std::string::npos) << info;
  }
}

TEST(ExportedServoAmplifier, RefusesAParticipantOfAnotherTypeNamingTheScene) {
  const config::Scene scene = config::load_scene(kScene);
  try {
    export_config(scene, {"tachometer", "servo", 2, "x.fmu", MECHSIM_FMU_BINARY});
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("participants.servo.type: participant 'servo' is a servo_amplifier, not a tachometer"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(export_config(scene, {"tachometer", "nope", 2, "x.fmu", MECHSIM_FMU_BINARY}), std::invalid_argument);
}

// What the exported binary refuses, through the importer: a parameter after initialization,
// a step from another time than the FMU's (it cannot go back), a negative time constant
// (the node type's own check, reported as the FMU's error with its message).
TEST(ExportedServoAmplifier, RefusesWhatItCannotDoWithTheReasonInTheFmusLog) {
  const config::Scene scene = config::load_scene(kScene);
  Scratch scratch;
  const std::string file = scratch.path("servo.fmu");
  export_participant(scene, "servo_amplifier", "servo", 2, file);
  const fmi::FmuArchive archive(fmi::FmuLabel{file, "servo"});
  const auto& d = archive.description();
  const auto expect_refusal = [](const auto& call, const std::string& expected) {
    try {
      call();
      ADD_FAILURE() << "expected a refusal containing: " << expected;
    } catch (const fmi::FmuError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  {
    const auto fmu = fmi::FmuInstance::create(archive, fmi::InterfaceKind::co_simulation, "servo");
    fmu->enter_initialization(0.0, 1.0);
    fmu->set_real(variable(d, "integral_time").value_reference, -1.0);
    expect_refusal([&] { fmu->exit_initialization(); }, "integral_time");
  }
  const auto fmu = fmi::FmuInstance::create(archive, fmi::InterfaceKind::co_simulation, "servo");
  fmu->enter_initialization(0.0, 1.0);
  fmu->exit_initialization();
  expect_refusal([&] { fmu->set_real(variable(d, "position_gain").value_reference, 30.0); },
                 "parameter 'position_gain' can be set only before initialization ends");
  fmu->do_step(0.0, 1e-3);
  expect_refusal([&] { fmu->do_step(0.0, 1e-3); }, "do_step from t = 0 s, but the FMU is at t = 0.001 s");
}

// Same bytes: the FMU's binary runs the same block code and the same SUNDIALS integrator with
// the scene's solver settings as a node does, so stepped with the same held inputs it gives
// the native block's outputs bit for bit. The native side is what cosim::NodeStepper does in
// a step: restart the integrator (the inputs start afresh), integrate to t_k+1 with the
// inputs held, then evaluate the outputs at t_k+1 with the inputs of t_k+1; the FMU side is
// what a co-simulation master does: set u(t_k), fmiXDoStep(t_k, H), set u(t_k+1), get y.
// The inputs are smooth test signals (each input its own sine), 400 steps of the scene's
// macro step: the NC loop's servo and tacho (the tacho with the compliant coupling element
// at its cut) at 25 us, cam_press.yaml's cam shaft at 1 ms and cam_lift_off.yaml's flexible
// follower at 0.5 ms (it lifts off: contact events located inside the steps by the FMU's
// integrator, checked by its lift_off_count). For the servo a
// parameter is also changed through the FMU (position_gain 40 -> 30 1/s) against the native
// block built with the scene's --set, to show that FMU parameters reach the block.
TEST_P(ExportedParticipantFmu, SteppedByTheImporterGivesTheNativeBlocksOutputsBitForBit) {
  const Case c = GetParam();
  const bool change_gain = std::string(c.type) == "servo_amplifier";
  const std::string scene_file = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + c.scene;
  const config::Scene scene = config::load_scene(scene_file);
  const config::Scene native_scene = change_gain
                                         ? config::load_scene(scene_file, {"participants.servo.params.position_gain=30 1/s"})
                                         : config::load_scene(scene_file);
  Scratch scratch;
  const std::string file = scratch.path(std::string(c.participant) + ".fmu");
  const ExportConfig exported = export_participant(scene, c.type, c.participant, c.fmi, file);

  // Native: the block as the node type builds it, integrated as the node integrates it.
  const ExportConfig native_config = export_config(native_scene, {c.type, c.participant, c.fmi, "", ""});
  const auto native = cosim::find_node_type(c.type)->make_block(
      native_config.params, native_config.coupling ? &*native_config.coupling : nullptr);
  const double h = scene.time.step, t0 = 0.0;
  const int steps = 400;
  std::vector<double> x0(native->num_states());
  native->initial_state(t0, x0);
  solve::BlockIntegrator integrator(*native, cosim::solver_options(native_config.solver), t0, x0);
  const int ni = native->num_inputs(), no = native->num_outputs();
  // A shaft `speed` input turns at 100 rad/s (with a ripple), so that a follower's inertia
  // overcomes its spring and it lifts off: state events inside the steps.
  const int speed = native->input_index("speed");
  const auto inputs_at = [&](double t, std::span<double> u) {
    for (int i = 0; i < ni; ++i) u[i] = 0.2 * (i + 1) * std::sin(2 * std::numbers::pi * 40.0 * (i + 1) * t);
    if (speed >= 0) u[speed] += 100.0;
  };

  // The FMU through the importer.
  const fmi::FmuArchive archive(fmi::FmuLabel{file, c.participant});
  const auto fmu = fmi::FmuInstance::create(archive, fmi::InterfaceKind::co_simulation, c.participant);
  const fmi::ModelDescription& d = archive.description();
  std::vector<const fmi::Variable*> in(ni), out(no);
  const ExportedParticipant names(exported);  // the FMU's names of the block's ports
  for (const auto& v : names.variables())
    if (v.kind == VariableKind::input) in[v.index] = &variable(d, v.name);
  for (int i = 0; i < no; ++i) out[i] = &variable(d, native->outputs()[i].name);
  fmu->enter_initialization(t0, t0 + steps * h);
  if (change_gain) fmu->set_real(variable(d, "position_gain").value_reference, 30.0);
  std::vector<double> u(ni), y(no), y_fmu(no);
  inputs_at(t0, u);
  for (int i = 0; i < ni; ++i) fmu->set_real(in[i]->value_reference, u[i]);
  fmu->exit_initialization();

  int differing = 0;
  double worst = 0.0;
  const auto compare = [&](double t) {
    native->calc_outputs(t, integrator.state(), u, y);
    for (int o = 0; o < no; ++o) {
      y_fmu[o] = fmu->get_real(out[o]->value_reference);
      if (std::memcmp(&y[o], &y_fmu[o], sizeof(double)) != 0) {
        ++differing;
        worst = std::max(worst, std::abs(y[o] - y_fmu[o]) / std::max(1.0, std::abs(y[o])));
      }
    }
  };
  compare(t0);
  const double first_output_at_t0 = y[0];
  double first_output_swing = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double t = t0 + k * h, t_next = t0 + (k + 1) * h;
    const std::vector<double> held = u;
    integrator.mark_discontinuity();
    integrator.advance_to(t_next, [&](double, std::span<double> v) { std::copy(held.begin(), held.end(), v.begin()); });
    fmu->do_step(t, t_next - t);
    inputs_at(t_next, u);
    for (int i = 0; i < ni; ++i) fmu->set_real(in[i]->value_reference, u[i]);
    compare(t_next);
    first_output_swing = std::max(first_output_swing, std::abs(y[0] - first_output_at_t0));
  }
  EXPECT_EQ(differing, 0) << "worst relative difference " << worst;
  // The signals moved: the comparison was not of two constants.
  EXPECT_GT(first_output_swing, 1e-6);
  // The follower lost contact at least once: its events were located inside the steps.
  if (const int lift_offs = native->output_index("lift_off_count"); lift_offs >= 0) {
    EXPECT_GT(y[lift_offs], 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(NcSlideLoop, ExportedParticipantFmu,
                         ::testing::Values(Case{"servo_amplifier", "servo", 2}, Case{"servo_amplifier", "servo", 3},
                                           Case{"tachometer", "tacho", 2}, Case{"tachometer", "tacho", 3},
                                           Case{"cam_shaft", "cam", 2, "cam_press.yaml"},
                                           Case{"follower", "follower", 3, "cam_lift_off.yaml"}),
                         [](const auto& info) {
                           return std::string(info.param.participant) + "_fmi" + std::to_string(info.param.fmi);
                         });

// The scene with the exported servo FMU in place of the native amplifier
// (`participants.servo.fmu:`), macro step h, 20 ms, run in process; returns the worst
// difference of the node logs to the native scene's at the same step, in each signal's range.
double worst_difference_in_the_loop(const Scratch& scratch, const std::string& fmu, const std::string& step,
                                    std::string& where) {
  std::ifstream in(kScene);
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string anchor = "    type: servo_amplifier\n";
  yaml.insert(yaml.find(anchor) + anchor.size(), "    fmu: {file: " + fmu + ", interface: co-simulation}\n");
  const std::string scene_file = scratch.path("with_fmu_" + step + ".yaml");
  std::ofstream(scene_file) << yaml;
  const std::vector<std::string> overrides{"time.end=0.02 s", "time.step=" + step};
  const std::string fmu_run = scratch.path("fmu_run_" + step), native_run = scratch.path("native_run_" + step);
  fs::create_directories(fmu_run);
  fs::create_directories(native_run);
  cosim::InprocRunOptions fmu_options, native_options;
  fmu_options.run_dir = fmu_run;
  native_options.run_dir = native_run;
  const auto with_fmu = cosim::run_inproc(config::load_scene(scene_file, overrides), fmu_options);
  EXPECT_TRUE(with_fmu.ok) << with_fmu.reason;
  const auto native = cosim::run_inproc(config::load_scene(kScene, overrides), native_options);
  EXPECT_TRUE(native.ok) << native.reason;
  double worst = 0.0;
  for (const char* node : {"servo", "tacho", "slide"}) {
    const std::string log = std::string("/") + node + ".outputs.bin";
    const cosim::OutputLog a = cosim::read_output_log(native_run + log), b = cosim::read_output_log(fmu_run + log);
    EXPECT_EQ(a.columns, b.columns);
    for (std::size_t c = 1; c < std::min(a.columns.size(), b.columns.size()); ++c) {
      const double range = std::max(cosim::finite_range(a.data[c]), 1e-12);
      for (std::size_t i = 0; i < std::min(a.data[c].size(), b.data[c].size()); ++i)
        if (std::abs(a.data[c][i] - b.data[c][i]) / range > worst) {
          worst = std::abs(a.data[c][i] - b.data[c][i]) / range;
          where = std::string(node) + "." + a.columns[c];
        }
    }
  }
  return worst;
}

// Round trip in the run: the exported servo amplifier (FMI 2, co-simulation, stepped every
// macro step by the importer's CoSimulationBlock) plays `servo` in the NC loop, lock-step
// over the in-process transport, against the native amplifier. Not the same bytes, and it
// cannot be: the importer samples a co-simulation FMU's inputs at the step's start and holds
// them (the master's zero-order hold, co_simulation_block.h), one sample behind the native
// node, which integrates with its edges' linear extrapolation of the newest samples. That
// difference is of first order in the macro step, so the test asks what first order means:
// halving the step halves it (ratio in [0.35, 0.65]), and at the scene's 25 us it stays
// below the co-simulation's own error against the monolithic reference (0.70 % of range,
// config/scenes/nc_slide_loop.yaml). A wrong law or a wrong parameter in the FMU does not
// shrink with the step.
TEST(ExportedServoAmplifier, PlaysTheServoInTheNcLoopWithAFirstOrderDifferenceToTheNative) {
  const config::Scene scene = config::load_scene(kScene);
  Scratch scratch;
  const std::string file = scratch.path("servo.fmu");
  export_participant(scene, "servo_amplifier", "servo", 2, file);
  std::string where_h, where_half;
  const double at_h = worst_difference_in_the_loop(scratch, file, "25 us", where_h);
  const double at_half = worst_difference_in_the_loop(scratch, file, "12.5 us", where_half);
  std::printf("exported servo in the NC loop: worst %.3g of range at 25 us (%s), %.3g at 12.5 us (%s)\n", at_h,
              where_h.c_str(), at_half, where_half.c_str());
  EXPECT_LT(at_h, 7e-3) << where_h;
  EXPECT_GT(at_h, 0.0);
  EXPECT_GT(at_half / at_h, 0.35) << where_half;
  EXPECT_LT(at_half / at_h, 0.65) << where_half;
}

// FMU state through the binary's own FMI 2 functions (the importer does not call them yet):
// the exported tachometer stepped 200 steps, its state taken, 200 more steps recorded; then
// the state serialized, read back, set into the same instance and into a second one, and
// the same 200 steps repeated: the outputs are the recorded ones bit for bit, since a step
// restarts the integrator from the state at its start whether or not the state was set.
TEST(ExportedTachometer, FmuStateRollsBackAndMovesToAnotherInstanceBitForBit) {
  const config::Scene scene = config::load_scene(kScene);
  Scratch scratch;
  const std::string file = scratch.path("tacho.fmu");
  export_participant(scene, "tachometer", "tacho", 2, file);
  const fmi::FmuArchive archive(fmi::FmuLabel{file, "tacho"});
  const auto& d = archive.description();
  void* library = dlopen(archive.binary_path(fmi::InterfaceKind::co_simulation).c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(library, nullptr) << dlerror();
  const auto fn = [&](const char* name) {
    void* f = dlsym(library, name);
    if (f == nullptr) throw std::runtime_error(std::string("missing ") + name);
    return f;
  };
  using GetState = fmi2Status(fmi2Component, fmi2FMUstate*);
  using SetState = fmi2Status(fmi2Component, fmi2FMUstate);
  using StateSize = fmi2Status(fmi2Component, fmi2FMUstate, size_t*);
  using Serialize = fmi2Status(fmi2Component, fmi2FMUstate, char[], size_t);
  using Deserialize = fmi2Status(fmi2Component, const char[], size_t, fmi2FMUstate*);
  auto* instantiate = reinterpret_cast<fmi2InstantiateTYPE*>(fn("fmi2Instantiate"));
  auto* setup = reinterpret_cast<fmi2SetupExperimentTYPE*>(fn("fmi2SetupExperiment"));
  auto* enter = reinterpret_cast<fmi2EnterInitializationModeTYPE*>(fn("fmi2EnterInitializationMode"));
  auto* exit = reinterpret_cast<fmi2ExitInitializationModeTYPE*>(fn("fmi2ExitInitializationMode"));
  auto* set_real = reinterpret_cast<fmi2SetRealTYPE*>(fn("fmi2SetReal"));
  auto* get_real = reinterpret_cast<fmi2GetRealTYPE*>(fn("fmi2GetReal"));
  auto* do_step = reinterpret_cast<fmi2DoStepTYPE*>(fn("fmi2DoStep"));
  auto* free_instance = reinterpret_cast<fmi2FreeInstanceTYPE*>(fn("fmi2FreeInstance"));
  auto* get_state = reinterpret_cast<GetState*>(fn("fmi2GetFMUstate"));
  auto* set_state = reinterpret_cast<SetState*>(fn("fmi2SetFMUstate"));
  auto* free_state = reinterpret_cast<GetState*>(fn("fmi2FreeFMUstate"));
  auto* state_size = reinterpret_cast<StateSize*>(fn("fmi2SerializedFMUstateSize"));
  auto* serialize = reinterpret_cast<Serialize*>(fn("fmi2SerializeFMUstate"));
  auto* deserialize = reinterpret_cast<Deserialize*>(fn("fmi2DeSerializeFMUstate"));

  fmi2CallbackFunctions callbacks{};
  const std::string resources = archive.resource_location();
  const auto start = [&] {
    fmi2Component c = instantiate("tacho", fmi2CoSimulation, d.instantiation_token.c_str(), resources.c_str(), &callbacks,
                                  fmi2False, fmi2False);
    EXPECT_NE(c, nullptr);
    EXPECT_EQ(setup(c, fmi2False, 0.0, 0.0, fmi2True, 1.0), fmi2OK);
    EXPECT_EQ(enter(c), fmi2OK);
    EXPECT_EQ(exit(c), fmi2OK);
    return c;
  };
  std::vector<fmi2ValueReference> inputs, outputs;
  for (const auto& v : d.variables) {
    if (v.causality == fmi::Causality::input) inputs.push_back(v.value_reference);
    if (v.causality == fmi::Causality::output) outputs.push_back(v.value_reference);
  }
  const double h = scene.time.step;
  // Steps k0 .. k0+n-1 of component c, inputs a sine per input; the outputs after each.
  const auto run = [&](fmi2Component c, int k0, int n) {
    std::vector<double> trace, u(inputs.size()), y(outputs.size());
    for (int k = k0; k < k0 + n; ++k) {
      for (std::size_t i = 0; i < u.size(); ++i) u[i] = 0.3 * (i + 1) * std::sin(2 * std::numbers::pi * 60.0 * (i + 1) * k * h);
      EXPECT_EQ(set_real(c, inputs.data(), inputs.size(), u.data()), fmi2OK);
      EXPECT_EQ(do_step(c, k * h, (k + 1) * h - k * h, fmi2True), fmi2OK);
      EXPECT_EQ(get_real(c, outputs.data(), outputs.size(), y.data()), fmi2OK);
      trace.insert(trace.end(), y.begin(), y.end());
    }
    return trace;
  };
  fmi2Component first = start();
  run(first, 0, 200);
  fmi2FMUstate at_200 = nullptr;
  ASSERT_EQ(get_state(first, &at_200), fmi2OK);
  const std::vector<double> recorded = run(first, 200, 200);

  size_t size = 0;
  ASSERT_EQ(state_size(first, at_200, &size), fmi2OK);
  std::vector<char> bytes(size);
  ASSERT_EQ(serialize(first, at_200, bytes.data(), size), fmi2OK);
  fmi2FMUstate read_back = nullptr;
  ASSERT_EQ(deserialize(first, bytes.data(), size, &read_back), fmi2OK);

  ASSERT_EQ(set_state(first, read_back), fmi2OK);  // rollback
  const std::vector<double> again = run(first, 200, 200);
  EXPECT_EQ(std::memcmp(again.data(), recorded.data(), recorded.size() * sizeof(double)), 0);

  fmi2Component second = start();  // a fresh instance, set to the state of another
  ASSERT_EQ(set_state(second, read_back), fmi2OK);
  const std::vector<double> moved = run(second, 200, 200);
  EXPECT_EQ(std::memcmp(moved.data(), recorded.data(), recorded.size() * sizeof(double)), 0);
  EXPECT_GT(std::abs(recorded.back() - recorded[outputs.size() - 1]), 0.0);  // the outputs moved

  EXPECT_EQ(free_state(first, &at_200), fmi2OK);
  EXPECT_EQ(free_state(first, &read_back), fmi2OK);
  EXPECT_EQ(read_back, nullptr);
  free_instance(first);
  free_instance(second);
  dlclose(library);
}

// The command end to end: `mechsim fmu export` writes an FMU the importer opens (with the
// binary found next to the executable), and a wrong type is refused with exit status 1 and
// the scene's key on stderr.
TEST(FmuExportCommand, WritesAnFmuAndRefusesAWrongType) {
  const std::string mechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
  ASSERT_TRUE(fs::exists(mechsim)) << mechsim;
  Scratch scratch;
  const auto run = [&](const std::string& args) {
    const std::string command = mechsim + " fmu export " + args + " > " + scratch.path("out.txt") + " 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(scratch.path("out.txt"));
    std::stringstream out;
    out << in.rdbuf();
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, out.str());
  };
  const std::string file = scratch.path("tacho.fmu");
  const auto [ok, out] = run("tachometer --scene " + kScene + " --participant tacho --fmi 3 -o " + file);
  ASSERT_EQ(ok, 0) << out;
  const fmi::FmuArchive archive(fmi::FmuLabel{file, "tacho"});
  EXPECT_EQ(archive.description().version, fmi::FmiVersion::fmi3);
  EXPECT_EQ(variable(archive.description(), "armature_voltage").causality, fmi::Causality::input);
  const auto [refused, message] = run("cam_shaft --scene " + kScene + " --participant tacho -o " + scratch.path("x.fmu"));
  EXPECT_EQ(refused, 1) << message;
  EXPECT_NE(message.find("participants.tacho.type: participant 'tacho' is a tachometer, not a cam_shaft"), std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(scratch.path("x.fmu")));
}

}  // namespace
}  // namespace mechsim::fmi_export
