// An outsider on a run's domain (issue 15's scenario, docs/faults.md 'Foreign writers'): a
// participant written only from idl/servo.idl joins a running nc_slide_loop, reads the run
// id from the first servo/command sample and publishes forged samples with that run id and
// the next step numbers. The tachometer must not use them: the run fails with exit 1 and a
// message naming the topic and the foreign writer, never "ok".
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <vector>

#include "domain_lock.h"
#include "mechsim/transport/backends.h"
#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;

// nc_slide_loop for 60 s of simulated time on a domain of its own, as an outsider would find
// it running; the launcher's loopback configuration for this process too.
struct RunningScene {
  launch::DomainLock domain = launch::DomainLock::acquire();
  fs::path dir;
  pid_t launcher = -1;
  explicit RunningScene(const std::string& tag) : dir(fs::temp_directory_path() / ("mechsim-" + tag + "-" + std::to_string(::getpid()))) {
    fs::create_directories(dir);
    ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
    launcher = spawn({std::string(MECHSIM_BIN_DIR) + "/mechsim", "launch", MECHSIM_SOURCE_DIR "/config/scenes/nc_slide_loop.yaml", "--end",
                      "60 s", "--no-plot", "--no-progress", "--runs-dir", (dir / "runs").string(), "--set",
                      "dds.domain=" + std::to_string(domain.domain_id())},
                     log());
  }
  ~RunningScene() {
    if (launcher > 0) wait_for(launcher, log(), 30);
    fs::remove_all(dir);
  }
  std::string log() const { return (dir / "launch.log").string(); }
  CommandResult wait() {
    CommandResult r = wait_for(launcher, log(), 60);
    launcher = -1;
    return r;
  }
};

bool has_cyclone() {
  const auto vendors = transport::available_vendors();
  return std::find(vendors.begin(), vendors.end(), "cyclone") != vendors.end();
}

TEST(ForeignWriter, ForgedServoCommandsFailTheRunNamingTheTopicAndTheWriter) {
  if (!has_cyclone()) GTEST_SKIP() << "needs Cyclone DDS";
  RunningScene scene("foreign");
  {
    auto intruder = transport::create_participant("cyclone", scene.domain.domain_id());
    const transport::TopicType* type = transport::find_topic_type("ServoCommand");
    ASSERT_NE(type, nullptr);
    auto reader = intruder->create_reader("servo/command", *type);
    transport::SampleHeader h;
    std::vector<double> values;
    bool seen = false;
    for (int i = 0; i < 3000 && !seen; ++i) {
      seen = reader->take(h, values);
      if (!seen) intruder->wait(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(seen) << "no servo/command sample within 30 s:\n" << slurp(scene.log());
    auto writer = intruder->create_writer("servo/command", *type);
    std::vector<double> forged(type->fields.size(), 1e6);  // armature voltage 1e6 V, ...
    for (int i = 0; i < 200 && writer->matched_readers() < 1; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    while (reader->take(h, values)) {
    }
    for (std::uint64_t k = 1; k <= 200; ++k) writer->write({h.run_id, h.step + k, h.t}, forged);
    const CommandResult r = scene.wait();
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("foreign data on topic 'servo/command'"), std::string::npos) << r.output;
    // Both writers are named, the intruder with its process (this test).
    EXPECT_NE(r.output.find("process servo_amplifier"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("process foreign_writer_test (pid " + std::to_string(::getpid()) + ")"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("steps/s"), std::string::npos) << "a corrupted run must not report success:\n" << r.output;
  }
}


}  // namespace
}  // namespace mechsim::testing
