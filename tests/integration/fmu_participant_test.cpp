// Participants of type fmu over DDS (docs/fmi.md, "FMU participants"): real node processes
// started by `mechsim launch`, on Cyclone DDS, on Fast DDS and mixed. The scene is the
// shipped config/scenes/fmu_speed_lag.yaml with the test FMUs of this build: the cam
// shaft's constant speed w drives the lag T dy/dt = k u - y as a co-simulation FMU and as a
// model-exchange FMU, each checked against the closed form y(t) = k w (1 - exp(-t / T)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "mechsim/transport/domain_lock.h"
#include "mechsim/cosim/output_log.h"
#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kFmuDir = MECHSIM_TEST_FMU_DIR;
constexpr double kSpeed = std::numbers::pi;  // 30 rpm in rad/s
constexpr double kGain = 2.0, kTimeConstant = 0.05;

class FmuParticipants : public RunFolderTest {
 protected:
  // The shipped scene with its FMU paths pointing at this build's test FMUs, and `extra`
  // appended (more participants and connections).
  std::string scene(const std::string& extra = "") const {
    std::string text = slurp(scene_path("fmu_speed_lag.yaml"));
    for (std::string::size_type at; (at = text.find("../../build/tests/fmus")) != std::string::npos;)
      text.replace(at, std::string("../../build/tests/fmus").size(), kFmuDir);
    const std::string path = (dir_ / "fmu_speed_lag.yaml").string();
    std::ofstream(path) << text << extra;
    return path;
  }
  // y of `node` at every step against the closed form, to `tolerance` (rad/s).
  void expect_closed_form(const std::string& tag, const std::string& node, double tolerance) const {
    const cosim::OutputLog out = cosim::read_output_log((run_folder(tag) / (node + ".outputs.bin")).string());
    const int t = out.column("t"), y = out.column("y");
    ASSERT_GE(y, 0) << node << ": no column y";
    ASSERT_EQ(out.rows(), 301u) << node << ": steps 0 .. 300 of 1 ms";
    double worst = 0.0;
    for (std::size_t r = 0; r < out.rows(); ++r) {
      const double tr = out.data[t][r];
      const double expected = kGain * kSpeed * (1.0 - std::exp(-tr / kTimeConstant));
      worst = std::max(worst, std::abs(out.data[y][r] - expected));
    }
    EXPECT_LT(worst, tolerance) << node << " on " << tag;
  }
  void run_and_check(const std::string& tag, std::vector<std::string> extra) {
    CommandResult r = run(launch_args(scene(), tag, std::move(extra)), log(tag), 180);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // Co-simulation: RK4 substeps of 0.1 ms on T = 50 ms (tests/fmus/common/solver.c) are
    // exact to ~(h/T)^4 = 2e-11 of the response; 1e-8 rad/s is rounding headroom, and a
    // step's shift in time would show as 2 w k (1 ms / T) e^{-t/T}, up to 0.25 rad/s.
    expect_closed_form(tag, "lag", 1e-8);
    // Model exchange: CVODE at rtol 1e-9, atol 1e-12 (the scene's solver); measured 5.4e-7
    // rad/s from the reference (rtol 1e-10), about 1e-7 of 2 k w = 6.3 rad/s, as the error
    // control lets it accumulate over ~4400 steps. 1e-5 rad/s leaves room for another
    // machine's step choices and still sees a step's shift (up to 0.25 rad/s).
    expect_closed_form(tag, "filter", 1e-5);
    const json s = summary(tag);
    EXPECT_EQ(s["status"], "ok") << s.dump(2);
    EXPECT_EQ(s["complete"], true);
    // The step each node reached (its end record), on every vendor: not the last status heard.
    for (const char* node : {"cam", "lag", "filter"}) {
      EXPECT_EQ(s["nodes"][node]["last_step"], 300) << node << " on " << tag;
      EXPECT_EQ(s["nodes"][node]["reached_end"], true) << node << " on " << tag;
    }
  }
};

TEST_F(FmuParticipants, CoSimulationAndModelExchangeFmusOnCyclone) {
  run_and_check("cyclone", {"--set", "dds.vendor=cyclone"});
}

TEST_F(FmuParticipants, CoSimulationAndModelExchangeFmusOnFastDds) {
  run_and_check("fastdds", {"--set", "dds.vendor=fastdds"});
}

TEST_F(FmuParticipants, MixedVendors) {
  // The cam on Cyclone, the co-simulation FMU on Fast DDS, the model-exchange one on Cyclone.
  run_and_check("mixed", {"--set", "dds.vendor=cyclone", "--set", "participants.lag.dds=fastdds"});
}

TEST_F(FmuParticipants, FmuOutputsCrossVendorsUnchanged) {
  // The filter reads the co-simulation FMU's y (FmuOutputs) instead of the cam's speed; with
  // the lag on Fast DDS and the filter on Cyclone the node logs are the bytes of the run
  // with every node on Cyclone.
  const std::vector<std::string> rewired{"--set", "connections[1].from=lag.y"};
  auto with = [&](std::vector<std::string> more) {
    more.insert(more.end(), rewired.begin(), rewired.end());
    return more;
  };
  CommandResult one = run(launch_args(scene(), "one", with({"--set", "dds.vendor=cyclone"})), log("one"), 180);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  CommandResult mixed = run(launch_args(scene(), "mixed", with({"--set", "dds.vendor=cyclone", "--set", "participants.lag.dds=fastdds"})),
                            log("mixed"), 180);
  ASSERT_EQ(mixed.exit_code, 0) << mixed.output;
  expect_identical_node_outputs(run_folder("one"), run_folder("mixed"), std::vector<std::string>{"cam", "lag", "filter"},
                                "Cyclone only and mixed");
}

// The variable names away from the nodes: `topic echo` on the running scene (with
// --scene: the FMU's names; without: reals[i]), and the launcher's recording, whose
// FmuOutputs channels carry them as "mechsim.fields" metadata (bag info, bag export).
TEST_F(FmuParticipants, EchoAndTheRecordingNameTheVariables) {
  const transport::DomainLock domain = transport::DomainLock::acquire();
  const std::string path = scene();
  // Paced at real time for 3 s, so that the echoes find the writers while they run.
  const pid_t launcher = spawn(launch_args(path, "rec", {"--set", "dds.domain=" + std::to_string(domain.domain_id()), "--set",
                                                         "record=true", "--set", "mode=realtime", "--set", "time.end=3 s"}),
                               log("rec"));
  CommandResult named = run({kMechsim, "topic", "echo", "lag/outputs", "--domain", std::to_string(domain.domain_id()),
                             "--count", "2", "--timeout", "60", "--scene", path},
                            log("echo-named"), 90);
  EXPECT_EQ(named.exit_code, 0) << named.output;
  EXPECT_NE(named.output.find("--- # lag/outputs (mechsim::msg::FmuOutputs)"), std::string::npos) << named.output;
  EXPECT_NE(named.output.find("\ny: "), std::string::npos) << named.output;
  CommandResult unnamed = run({kMechsim, "topic", "echo", "filter/outputs", "--domain", std::to_string(domain.domain_id()),
                               "--count", "1", "--timeout", "60"},
                              log("echo-unnamed"), 90);
  EXPECT_EQ(unnamed.exit_code, 0) << unnamed.output;
  EXPECT_NE(unnamed.output.find("\nreals[0]: "), std::string::npos) << unnamed.output;
  CommandResult launched = wait_for(launcher, log("rec"), 120);
  ASSERT_EQ(launched.exit_code, 0) << launched.output;

  const std::string mcap = (run_folder("rec") / "recording.mcap").string();
  CommandResult info = run({kMechsim, "bag", "info", mcap}, log("info"), 60);
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("fields: y:f64"), std::string::npos) << info.output;
  CommandResult exported = run({kMechsim, "bag", "export", mcap, "--csv", (dir_ / "csv").string()}, log("export"), 60);
  EXPECT_EQ(exported.exit_code, 0) << exported.output;
  const std::string csv = slurp((dir_ / "csv" / "lag_outputs.csv").string());
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,step,run_id,y") << csv.substr(0, 200);
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 3000) << "every step of 3 s at 1 ms";
}

// `--replay lag=FILE` stands in for the FMU participant as for any other: the recording's
// FmuOutputs samples, decoded with the FMU's names from the plan, replayed; the filter that
// reads lag.y then writes the bytes it wrote in the recorded run.
TEST_F(FmuParticipants, AReplayStandsInForTheFmu) {
  const std::vector<std::string> rewired{"--set", "connections[1].from=lag.y", "--set", "record=true"};
  CommandResult recorded = run(launch_args(scene(), "recorded", rewired), log("recorded"), 180);
  ASSERT_EQ(recorded.exit_code, 0) << recorded.output;
  std::vector<std::string> replay = rewired;
  replay.insert(replay.end(), {"--replay", "lag=" + (run_folder("recorded") / "recording.mcap").string()});
  CommandResult replayed = run(launch_args(scene(), "replayed", replay), log("replayed"), 180);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  expect_identical_node_outputs(run_folder("recorded"), run_folder("replayed"), std::vector<std::string>{"lag", "filter"},
                                "recorded and replayed");
}

// An FMU that fails in a running node (tests/fmus/faulty, `fault` from fault_time = 50 ms
// on) ends the run cleanly with a message naming the FMU file, the participant, the
// function and the step; one that aborts its process is a node crash.
class FailingFmu : public RunFolderTest {
 protected:
  CommandResult run_faulty(const std::string& tag, const std::string& file, int fault) {
    const std::string path = (dir_ / (tag + ".yaml")).string();
    std::ofstream(path) << "scene: fmu_fault\n"
                        << "time: {start: 0 s, end: 0.1 s, step: 1 ms}\n"
                        << "participants:\n"
                        << "  cam: {type: cam_shaft, params: {speed: 30 rpm, pitch_radius: 65 mm, eccentricity: 0 mm,\n"
                        << "        law: [{type: full_cycloid, start: 0 deg, span: 180 deg, lift: 20 mm},\n"
                        << "              {type: full_cycloid, start: 180 deg, span: 180 deg, lift: -20 mm}]}}\n"
                        << "  bad: {type: fmu, fmu: " << kFmuDir << "/" << file
                        << ", parameters: {fault: " << fault << ", fault_time: 50 ms}}\n";
    return run(launch_args(path, tag), log(tag), 120);
  }
};

TEST_F(FailingFmu, AFailedStepEndsTheRunNamingFileParticipantFunctionAndStep) {
  CommandResult r = run_faulty("step", "faulty_fmi2_cs.fmu", 1);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  for (const std::string& part : {std::string("faulty_fmi2_cs.fmu"), std::string("participant 'bad'"),
                                  std::string("fmi2DoStep returned fmi2Error"), std::string("step 50 -> 51")})
    EXPECT_NE(r.output.find(part), std::string::npos) << part << " missing in:\n" << r.output;
  EXPECT_EQ(summary("step")["status"], "failed");
}

TEST_F(FailingFmu, ANanOutputEndsTheRunNamingTheOutput) {
  CommandResult r = run_faulty("nan", "faulty_fmi3_cs.fmu", 2);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  for (const std::string& part : {std::string("faulty_fmi3_cs.fmu"), std::string("participant 'bad'"),
                                  std::string("output 'y' is NaN"), std::string("step 49 -> 50")})
    EXPECT_NE(r.output.find(part), std::string::npos) << part << " missing in:\n" << r.output;
}

TEST_F(FailingFmu, AnFmuThatAbortsItsProcessIsANodeCrash) {
  CommandResult r = run_faulty("abort", "faulty_fmi2_cs.fmu", 3);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_FALSE(r.timed_out);
  EXPECT_NE(r.output.find("node 'bad' killed by signal 6 (Aborted)"), std::string::npos) << r.output;
  EXPECT_EQ(summary("abort")["status"], "failed");
}

// exit(0) inside the FMU's step at t = 50 ms of 100 ms: the exit code says nothing went
// wrong, but the node wrote no end record, so the run fails naming the node, the step and
// the exit, and its summary says it is incomplete.
TEST_F(FailingFmu, AnFmuThatExitsCleanlyMidRunFailsTheRunAsIncomplete) {
  CommandResult r = run_faulty("exit0", "faulty_fmi2_cs.fmu", 4);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_FALSE(r.timed_out);
  EXPECT_NE(r.output.find("node 'bad' ended early: exit code 0 at step 50 of 100, before its last step"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the run is incomplete"), std::string::npos) << r.output;
  const json s = summary("exit0");
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["complete"], false);
  EXPECT_EQ(s["failure"]["node"], "bad");
  EXPECT_EQ(s["failure"]["last_step"], 50);
  EXPECT_EQ(s["nodes"]["bad"]["last_step"], 50);
  EXPECT_EQ(s["nodes"]["bad"]["reached_end"], false);
}

}  // namespace
}  // namespace mechsim::testing
