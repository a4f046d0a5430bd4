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

#include "mechsim/transport/domain_lock.h"
#include "mechsim/transport/backends.h"
#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;

// nc_slide_loop for 60 s of simulated time on a domain of its own, as an outsider would find
// it running; the launcher's loopback configuration for this process too. A process per
// participant: in one process (the default) the members read each other's topics from
// memory, where a forged DDS sample never arrives, and so is not seen either
// (docs/faults.md, "Foreign writers").
struct RunningScene {
  transport::DomainLock domain = transport::DomainLock::acquire();
  fs::path dir;
  pid_t launcher = -1;
  explicit RunningScene(const std::string& tag, const std::string& vendor = "cyclone")
      : dir(fs::temp_directory_path() / ("mechsim-" + tag + "-" + std::to_string(::getpid()))) {
    fs::create_directories(dir);
    ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
    ::setenv("FASTRTPS_DEFAULT_PROFILES_FILE", MECHSIM_SOURCE_DIR "/config/dds/fastdds-shm.xml", 1);
    launcher = spawn({std::string(MECHSIM_BIN_DIR) + "/mechsim", "launch", MECHSIM_SOURCE_DIR "/config/scenes/nc_slide_loop.yaml", "--end",
                      "60 s", "--no-plot", "--no-progress", "--runs-dir", (dir / "runs").string(), "--dds", vendor, "--set",
                      "dds.domain=" + std::to_string(domain.domain_id()), "--set", "processes=per_participant"},
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

bool has_vendor(const std::string& vendor) {
  const auto vendors = transport::available_vendors();
  return std::find(vendors.begin(), vendors.end(), vendor) != vendors.end();
}
bool has_cyclone() { return has_vendor("cyclone"); }

// The first sample of `topic` a participant of `vendor` sees on the scene's domain: what an
// outsider reads the run id from.
transport::SampleHeader first_sample(transport::Participant& intruder, const std::string& topic, const std::string& type_name,
                                     const RunningScene& scene) {
  const transport::TopicType* type = transport::find_topic_type(type_name);
  EXPECT_NE(type, nullptr);
  auto reader = intruder.create_reader(topic, *type);
  transport::SampleHeader h;
  std::vector<double> values;
  for (int i = 0; i < 3000; ++i) {
    if (reader->take(h, values)) return h;
    intruder.wait(std::chrono::milliseconds(10));
  }
  ADD_FAILURE() << "no " << topic << " sample within 30 s:\n" << slurp(scene.log());
  return h;
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

// A forged command on mechsim/control with the run id read off the wire: "stop" would end
// the run early as if finished. Every node takes commands only from the launcher's writer
// (its GUID is on the node's command line), so the run fails naming the intruder's writer.
class ForeignControl : public ::testing::TestWithParam<std::string> {};

TEST_P(ForeignControl, AForgedStopCommandFailsTheRunNamingTheWriter) {
  const std::string vendor = GetParam();
  if (!has_vendor(vendor)) GTEST_SKIP() << "needs " << vendor;
  RunningScene scene("foreign-control-" + vendor, vendor);
  {
    auto intruder = transport::create_participant(vendor, scene.domain.domain_id());
    const transport::SampleHeader h = first_sample(*intruder, "servo/command", "ServoCommand", scene);
    auto control = intruder->create_control_writer();
    for (int i = 0; i < 200 && control->matched_readers() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    transport::ControlMessage stop;
    stop.run_id = h.run_id;
    stop.command = transport::ControlCommand::stop;
    control->write(stop);
    const CommandResult r = scene.wait();
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("foreign data on topic 'mechsim/control'"), std::string::npos) << r.output;
    ASSERT_FALSE(control->guid().empty());
    EXPECT_NE(r.output.find("from writer " + control->guid()), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("steps/s"), std::string::npos) << "a corrupted run must not report success:\n" << r.output;
  }
}

INSTANTIATE_TEST_SUITE_P(Vendors, ForeignControl, ::testing::Values("cyclone", "fastdds"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace mechsim::testing
