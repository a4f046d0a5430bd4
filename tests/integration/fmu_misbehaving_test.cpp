// FMUs that misbehave, each in one way (issue 38 items 2-5, docs/fmi.md "FMUs that
// misbehave"), through `mechsim check` and `mechsim launch`: each gives its clear error and
// leaves nothing behind, neither a mechsim-fmu-* folder in the temporary directory (TMPDIR
// is one of the test's own) nor the run folder's fmu/ unpack folder.
//  - fmi2Instantiate aborts (tests/fmus faulty_abort_instance): check and launch survive it,
//    since the FMU is instantiated in a child process, and name the file and the signal;
//  - the step segfaults (faulty, fault 5): a node crash, the run fails;
//  - the step calls exit(0) (faulty, fault 4): the run fails as incomplete;
//  - a small archive with a file of zeros that unpacks past the ratio limit: refused with
//    the numbers before a byte is unpacked.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <zip.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kFmuDir = MECHSIM_TEST_FMU_DIR;

class MisbehavingFmu : public RunFolderTest {
 protected:
  void SetUp() override {
    RunFolderTest::SetUp();
    // The children inherit it: whatever they unpack outside the run folder lands here.
    tmp_ = dir_ / "tmp";
    fs::create_directories(tmp_);
    ::setenv("TMPDIR", tmp_.c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("TMPDIR");
    RunFolderTest::TearDown();
  }
  // The cam of 0.1 s in 1 ms steps, and the FMU `file` as participant 'bad'.
  std::string scene(const std::string& tag, const std::string& file, int fault, const std::string& extra = "") const {
    const std::string path = (dir_ / (tag + ".yaml")).string();
    std::ofstream(path) << "scene: fmu_misbehaves\n"
                        << "time: {start: 0 s, end: 0.1 s, step: 1 ms}\n"
                        << "participants:\n"
                        << "  cam: {type: cam_shaft, params: {speed: 30 rpm, pitch_radius: 65 mm, eccentricity: 0 mm,\n"
                        << "        law: [{type: full_cycloid, start: 0 deg, span: 180 deg, lift: 20 mm},\n"
                        << "              {type: full_cycloid, start: 180 deg, span: 180 deg, lift: -20 mm}]}}\n"
                        << "  bad: {type: fmu, fmu: " << file << ", parameters: {fault: " << fault << ", fault_time: 50 ms}"
                        << extra << "}\n";
    return path;
  }
  // Nothing unpacked is left: no mechsim-fmu-* in the temporary directory, no fmu/ in the run folder.
  void expect_nothing_left(const std::string& tag) const {
    for (const auto& e : fs::directory_iterator(tmp_))
      ADD_FAILURE() << "left in the temporary directory: " << e.path();
    if (fs::exists(dir_ / tag))
      for (const auto& run : fs::directory_iterator(dir_ / tag))
        EXPECT_FALSE(fs::exists(run.path() / "fmu")) << "the run folder's unpack folder is left: " << run.path() / "fmu";
  }
  CommandResult check(const std::string& scene_file, const std::string& tag) const {
    return run({kMechsim, "check", scene_file}, log(tag), 60);
  }
  fs::path tmp_;
};

TEST_F(MisbehavingFmu, AnAbortInInstantiateIsTheChildsNotTheCheckersNorTheLaunchers) {
  const std::string fmu = kFmuDir + "/faulty_abort_instance_fmi2_cs.fmu";
  const std::string file = scene("abort", fmu, 0);
  CommandResult c = check(file, "check");
  EXPECT_EQ(c.exit_code, 2) << c.output;
  for (const std::string& part : {"mechsim check: FMU '" + fmu + "' (participant 'bad')", std::string("killed by signal 6 (Aborted)"),
                                  std::string("mechsim fmu probe")})
    EXPECT_NE(c.output.find(part), std::string::npos) << part << " missing in:\n" << c.output;
  CommandResult l = run(launch_args(file, "abort"), log("abort"), 60);
  EXPECT_EQ(l.exit_code, 2) << l.output;
  EXPECT_NE(l.output.find("mechsim launch: FMU '" + fmu + "' (participant 'bad')"), std::string::npos) << l.output;
  EXPECT_NE(l.output.find("killed by signal 6 (Aborted)"), std::string::npos) << l.output;
  const json s = json::parse(slurp((run_folder("abort") / "summary.json").string()));
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["complete"], false);
  expect_nothing_left("abort");
}

TEST_F(MisbehavingFmu, ASegfaultInTheStepIsANodeCrashAndLeavesNoFolder) {
  CommandResult r = run(launch_args(scene("segv", kFmuDir + "/faulty_fmi3_cs.fmu", 5), "segv"), log("segv"), 120);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("node 'bad' killed by signal 11 (Segmentation fault)"), std::string::npos) << r.output;
  EXPECT_EQ(summary("segv")["complete"], false);
  expect_nothing_left("segv");
}

TEST_F(MisbehavingFmu, AnExitZeroInTheStepFailsTheRunAndLeavesNoFolder) {
  CommandResult r = run(launch_args(scene("exit0", kFmuDir + "/faulty_fmi3_cs.fmu", 4), "exit0"), log("exit0"), 120);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("node 'bad' ended early: exit code 0 at step 50 of 100"), std::string::npos) << r.output;
  EXPECT_EQ(summary("exit0")["complete"], false);
  expect_nothing_left("exit0");
}

// The faulty FMU with resources/zeros.bin: 32 MiB that deflate to ~32 kB.
std::string with_zeros(const fs::path& folder) {
  const fs::path out = folder / "zeros_fmi2_cs.fmu";
  fs::copy_file(kFmuDir + "/faulty_fmi2_cs.fmu", out);
  int error = 0;
  zip_t* z = zip_open(out.c_str(), 0, &error);
  if (!z) throw std::runtime_error("cannot open " + out.string());
  static const std::string zeros(32u << 20, '\0');
  zip_source_t* src = zip_source_buffer(z, zeros.data(), zeros.size(), 0);
  if (zip_file_add(z, "resources/zeros.bin", src, ZIP_FL_OVERWRITE) < 0 || zip_close(z) != 0)
    throw std::runtime_error("cannot add the zeros to " + out.string());
  return out.string();
}

TEST_F(MisbehavingFmu, AnArchiveBeyondTheRatioLimitIsRefusedWithTheNumbersBeforeUnpacking) {
  const std::string fmu = with_zeros(dir_);
  const std::string file = scene("zeros", fmu, 0);
  for (const std::string& tag : {std::string("check"), std::string("zeros")}) {
    CommandResult r = tag == "check" ? check(file, tag) : run(launch_args(file, tag), log(tag), 60);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    for (const std::string& part : {"FMU '" + fmu + "' (participant 'bad')", std::string("unpacks to 32.0"), std::string(" bytes) from a file of "),
                                    std::string(": 1; the limits are 2.00 GiB unpacked and a ratio of 200 : 1"),
                                    std::string("unpack_limits"), std::string("refused before unpacking")})
      EXPECT_NE(r.output.find(part), std::string::npos) << part << " missing in:\n" << r.output;
  }
  expect_nothing_left("zeros");
  // The scene raises the limit for this FMU: then it runs.
  CommandResult raised = run(launch_args(scene("raised", fmu, 0, ", unpack_limits: {ratio: 100000}"), "raised"), log("raised"), 120);
  EXPECT_EQ(raised.exit_code, 0) << raised.output;
  expect_nothing_left("raised");
}

}  // namespace
}  // namespace mechsim::testing
