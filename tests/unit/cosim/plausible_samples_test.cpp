// Plausible samples (docs/dds.md): a node refuses a received field that is not finite or
// outside the physical bounds of the topic table, naming topic, sender, step, field and
// value. Driven in process (the same run_node as the node processes): an amplifier given a
// 5 kV limit and a 100 mm step puts out about 2.5 kV at step 0, beyond the 1 kV bound of
// ServoCommand.armature_voltage, and the tachometer that reads it stops the run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "mechsim/cosim/inproc_run.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

namespace fs = std::filesystem;

TEST(PlausibleSamples, AVoltageBeyondThePhysicalBoundStopsTheRunNamingFieldValueStepAndSender) {
  const config::Scene scene = config::load_scene(testing::shipped_scene("nc_slide_loop.yaml"),
                                                 {"participants.servo.params.voltage_limit=5000 V",
                                                  "participants.servo.params.setpoint.distance=100 mm", "time.end=0.02 s"});
  const fs::path dir = fs::temp_directory_path() / ("mechsim-plausible-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  InprocRunOptions options;
  options.run_dir = dir.string();
  const InprocRunResult r = run_inproc(scene, options);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.failed_node, "tacho");
  EXPECT_NE(r.reason.find("implausible sample on topic 'servo/command' from participant 'servo', step 0: armature_voltage = "),
            std::string::npos)
      << r.reason;
  EXPECT_NE(r.reason.find("outside [-1000, 1000]"), std::string::npos) << r.reason;
  // Typed on the status (the launcher reads no text): the partner diverged or its data is
  // corrupt, so a stable macro step is worth looking for.
  for (const InprocNodeResult& n : r.nodes)
    EXPECT_EQ(n.last.error, n.name == "tacho" ? transport::NodeError::implausible_input : transport::NodeError::none) << n.name;
  EXPECT_TRUE(r.diverged);
  fs::remove_all(dir);
}

TEST(PlausibleSamples, TheShippedLimitIsInsideTheBound) {
  const config::Scene scene = config::load_scene(testing::shipped_scene("nc_slide_loop.yaml"), {"time.end=0.02 s"});
  const fs::path dir = fs::temp_directory_path() / ("mechsim-plausible-ok-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  InprocRunOptions options;
  options.run_dir = dir.string();
  const InprocRunResult r = run_inproc(scene, options);
  EXPECT_TRUE(r.ok) << r.reason;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mechsim::cosim
