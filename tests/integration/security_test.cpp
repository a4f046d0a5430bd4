// DDS Security (docs/security.md), with real processes and both vendors' built-in plugins:
//  - a secured run gives node outputs byte-identical to an unsecured one (Cyclone DDS,
//    Fast DDS; mixed: see MixedLayout);
//  - participants without a valid identity (an unsecured one, and one whose certificate
//    another CA signed) discover nothing of a secured run and nothing they write is used:
//    the run ends "ok" and byte-identical, where the same forgery fails an unsecured run
//    (foreign_writer_test);
//  - a participant with a valid certificate is refused a topic its permissions lack, for
//    writing and for reading;
//  - a scene whose security folder is missing, incomplete or has a readable key is refused
//    before anything starts, naming the file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include <fstream>
#include <optional>
#include <set>

#include "mechsim/transport/domain_lock.h"
#include "mechsim/config/scene.h"
#include "mechsim/cosim/scene_plan.h"
#include "security_init.h"
#include "mechsim/transport/backends.h"
#include "mechsim/transport/security.h"
#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;

bool compiled_in(const std::string& vendor) {
  const auto v = transport::available_vendors();
  return std::find(v.begin(), v.end(), vendor) != v.end();
}

const std::string kScene = scene_path("nc_slide_loop.yaml");

// Two security folders for nc_slide_loop, made once for the suite: `sec` (the run's) and
// `other` (the same identities under another CA: valid certificates nobody in the run trusts).
class Security : public RunFolderTest {
 public:
  static void SetUpTestSuite() {
    folders_ = fs::temp_directory_path() / ("mechsim-security-" + std::to_string(::getpid()));
    fs::remove_all(folders_);
    fs::create_directories(folders_);
    for (const char* name : {"sec", "other"}) {
      const CommandResult r = run({kMechsim, "security", "init", (folders_ / name).string(), kScene},
                                  (folders_ / (std::string(name) + ".log")).string(), 60);
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(folders_); }
  void SetUp() override {
    RunFolderTest::SetUp();
    // This process's own participants: the launcher's loopback profiles.
    ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
    ::setenv("FASTRTPS_DEFAULT_PROFILES_FILE", MECHSIM_SOURCE_DIR "/config/dds/fastdds-shm.xml", 1);
  }
  static std::string sec() { return (folders_ / "sec").string(); }
  static std::string sec_dir() { return sec(); }
  static std::string other() { return (folders_ / "other").string(); }
  std::vector<std::string> run_args(const std::string& tag, const std::string& layout, bool secured,
                                    std::vector<std::string> extra = {}) {
    std::vector<std::string> a{"--dds", layout};
    if (secured) a.insert(a.end(), {"--set", "dds.security=" + sec()});
    a.insert(a.end(), extra.begin(), extra.end());
    return launch_args(kScene, tag, a);
  }
  // A secured run (tag: its runs folder). A known defect, not yet fixed: a secured Fast DDS
  // run, signed or encrypted, now and then never gets its nodes matched (the PKI-DH
  // handshake between two Fast DDS 2.9 participants stalls; 2 of about 45 signed starts on a
  // loaded 2-core machine, and once an encrypted one in a suite run; "nodes not ready after
  // 30 s"; docs/security.md, 'Protection'). One more start is allowed for that refusal
  // alone, and said; `tag` then names the second run, which must pass every check.
  CommandResult run_secured(std::string& tag, const std::string& layout, const std::vector<std::string>& extra) {
    CommandResult r = run(run_args(tag, layout, true, extra), log(tag));
    if (layout == "fastdds" && r.exit_code != 0 && r.output.find("nodes not ready after") != std::string::npos) {
      std::fprintf(stderr, "note: secured Fast DDS run not ready (known intermittent start failure), starting once more:\n%s\n",
                   r.output.c_str());
      tag += "_again";
      r = run(run_args(tag, layout, true, extra), log(tag));
    }
    return r;
  }
  void expect_identical_outputs(const std::string& a, const std::string& b) {
    expect_identical_node_outputs(run_folder(a), run_folder(b), std::vector<std::string>{"servo", "tacho", "slide"}, a + " and " + b);
  }

  // A secured run with an outsider beside it that goes on until the test stops it, whatever
  // the machine's speed: paced at rtf 0.1 with its end 600 s away (1 h 40 min of wall time),
  // it is stopped with SIGINT once every node has written all the rows of the plain run
  // (`kEnd` simulated: at least 3 s of wall time at rtf 0.1, during which the outsider writes).
  // Pacing changes no number (Realtime.PacedAndLockStepRunsGiveBitIdenticalOutputs): the
  // plain run's output files are the first bytes of the secured run's.
  static constexpr const char* kEnd = "0.3 s";  // 12 000 steps
  void run_plain() {
    const CommandResult plain = run(run_args("plain", "cyclone", false, {"--end", kEnd}), log("plain"));
    ASSERT_EQ(plain.exit_code, 0) << plain.output;
  }
  pid_t spawn_secured(int domain_id) {
    return spawn(run_args("secured", "cyclone", true,
                          {"--end", "600 s", "--mode", "realtime", "--rtf", "0.1", "--set", "dds.domain=" + std::to_string(domain_id)}),
                 log("secured"));
  }
  // True once every node of the secured run has written at least `fraction` of the plain
  // run's output bytes (false when the run ended first: it failed).
  bool wait_secured_past(double fraction, pid_t launcher) {
    for (const char* node : {"servo", "tacho", "slide"}) {
      const auto plain = fs::file_size(run_folder("plain") / (std::string(node) + ".outputs.bin"));
      if (!wait_for_output_bytes("secured", node, static_cast<std::uintmax_t>(fraction * static_cast<double>(plain)), 300, launcher))
        return false;
    }
    return true;
  }
  // Stops the run (SIGINT: exit code 130, "interrupted") and checks that it failed for no
  // other reason and that every node's outputs begin with the plain run's bytes.
  void stop_and_compare(pid_t launcher) {
    ::kill(launcher, SIGINT);
    const CommandResult secured = wait_for(launcher, log("secured"), 60);
    EXPECT_EQ(secured.exit_code, 130) << secured.output;
    EXPECT_NE(secured.output.find("run failed: interrupted by signal"), std::string::npos) << secured.output;
    EXPECT_EQ(secured.output.find("foreign"), std::string::npos) << secured.output;
    for (const char* node : {"servo", "tacho", "slide"}) {
      const std::string file = std::string(node) + ".outputs.bin";
      const std::string plain = slurp((run_folder("plain") / file).string());
      const std::string paced = slurp((run_folder("secured") / file).string());
      EXPECT_GT(plain.size(), 1000u) << file;
      EXPECT_TRUE(paced.size() >= plain.size() && paced.compare(0, plain.size(), plain) == 0)
          << file << ": the secured run's first " << plain.size() << " bytes differ from the plain run's";
    }
  }
  static fs::path folders_;
};
fs::path Security::folders_;

// ---------------------------------------------------------------------------------------
// Same numbers secured and not.

class SecuredRun : public Security, public ::testing::WithParamInterface<std::string> {};

TEST_P(SecuredRun, NodeOutputsAreByteIdenticalToAnUnsecuredRun) {
  const std::string layout = GetParam();
  if (!compiled_in(layout)) GTEST_SKIP() << layout << " is not in this build";
  const CommandResult plain = run(run_args("plain", layout, false), log("plain"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  // Secured; on Cyclone with the launcher's recorder on (it uses the launcher's identity,
  // and is a Cyclone participant: on Fast DDS it would make the run mixed).
  const std::vector<std::string> record =
      layout == "cyclone" ? std::vector<std::string>{"--set", "record=true"} : std::vector<std::string>{};
  std::string tag = "secured";
  const CommandResult secured = run_secured(tag, layout, record);
  ASSERT_EQ(secured.exit_code, 0) << secured.output;
  EXPECT_NE(secured.output.find("DDS security: " + sec()), std::string::npos) << secured.output;
  expect_identical_outputs("plain", tag);
  if (!record.empty()) {
    const auto rec = summary(tag)["recording"];
    EXPECT_TRUE(rec["complete"].get<bool>()) << rec.dump(2);
  }
  EXPECT_EQ(summary(tag)["dds_security"], sec());
  EXPECT_TRUE(summary("plain")["dds_security"].is_null());
}

INSTANTIATE_TEST_SUITE_P(Vendors, SecuredRun, ::testing::Values("cyclone", "fastdds"),
                         [](const auto& info) { return info.param; });

// An adaptive macro step: the permissions of `security init` for such a scene let each node
// publish its step proposals and read everybody else's (<node>/step), and the secured run
// gives the bytes of the plain one.
TEST_F(Security, AnAdaptiveRunIsSecuredWithItsStepTopics) {
  if (!compiled_in("cyclone")) GTEST_SKIP() << "cyclone is not in this build";
  const std::vector<std::string> adaptive{"--end", "20 ms", "--set", "time.step=adaptive", "--set", "time.max=25 us",
                                          "--set", "time.min=0.1 us", "--set", "time.tolerance=1e-3"};
  const std::string dir = (folders_ / "adaptive").string();
  std::vector<std::string> init{kMechsim, "security", "init", dir, kScene};
  init.insert(init.end(), adaptive.begin() + 2, adaptive.end());  // the time keys (the end is no matter)
  const CommandResult made = run(init, log("adaptive_init"), 60);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_NE(slurp(dir + "/slide/permissions.xml").find("<topic>servo/step</topic>"), std::string::npos)
      << "the slide may not read the amplifier's step proposals";
  const CommandResult plain = run(run_args("plain", "cyclone", false, adaptive), log("plain"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  std::vector<std::string> secured_args = adaptive;
  secured_args.insert(secured_args.end(), {"--set", "dds.security=" + dir});
  const CommandResult secured = run(launch_args(kScene, "secured", [&] {
    std::vector<std::string> a{"--dds", "cyclone"};
    a.insert(a.end(), secured_args.begin(), secured_args.end());
    return a;
  }()), log("secured"));
  ASSERT_EQ(secured.exit_code, 0) << secured.output;
  expect_identical_outputs("plain", "secured");
}

// ---------------------------------------------------------------------------------------
// Outsiders.

// Acts as the run's servo amplifier would: reads tacho/state and writes forged
// servo/command samples until told to stop; returns what it saw. `forged` counts the
// samples written so far (the test reads it while the run goes on).
struct OutsiderReport {
  int samples_read = 0;
  int max_matched_writers = 0, max_matched_readers = 0;
};

OutsiderReport act_as_outsider(transport::Participant& participant, const std::atomic<bool>& stop, std::atomic<int>& forged) {
  OutsiderReport report;
  const transport::TopicType* type = transport::find_topic_type("ServoCommand");
  auto reader = participant.create_reader("tacho/state", *transport::find_topic_type("TachoState"));
  auto writer = participant.create_writer("servo/command", *type);
  std::vector<double> values(type->fields.size(), 1e6);
  transport::SampleHeader h;
  std::vector<double> read;
  for (std::uint64_t k = 0; !stop.load(); ++k) {
    while (reader->take(h, read)) ++report.samples_read;
    report.max_matched_writers = std::max(report.max_matched_writers, reader->matched_writers());
    report.max_matched_readers = std::max(report.max_matched_readers, writer->matched_readers());
    writer->write({0, k, 0.0}, values);
    ++forged;
    participant.wait(std::chrono::milliseconds(5));
  }
  return report;
}

TEST_F(Security, ParticipantsWithoutAValidIdentitySeeNothingAndChangeNothing) {
  if (!compiled_in("cyclone")) GTEST_SKIP() << "the outsiders are Cyclone DDS participants";
  run_plain();
  if (HasFatalFailure()) return;
  transport::DomainLock domain = transport::DomainLock::acquire();
  // Another CA's "servo": a well-formed identity with the permissions of the run's own
  // servo, which the run's CA did not sign.
  auto foreign = transport::create_participant("cyclone", domain.domain_id(), transport::SecurityIdentity{other(), "servo"});
  const pid_t launcher = spawn_secured(domain.domain_id());
  std::atomic<bool> stop{false};
  std::atomic<int> forged{0};
  OutsiderReport seen;
  std::thread outsider([&] { seen = act_as_outsider(*foreign, stop, forged); });
  // Stepping (a tenth of the plain run's rows), then past the plain run's end: the
  // outsider wrote in between, while the compared rows were computed.
  const bool stepping = wait_secured_past(0.1, launcher);
  const int forged_while_stepping = forged.load();
  const bool past = stepping && wait_secured_past(1.0, launcher);
  const int forged_past = forged.load();
  stop_and_compare(launcher);
  stop = true;
  outsider.join();
  ASSERT_TRUE(past) << "the secured run ended before it was told to";
  EXPECT_GT(forged_past, forged_while_stepping) << "the outsider must have written while the run went on";
  EXPECT_EQ(seen.samples_read, 0);
  EXPECT_EQ(seen.max_matched_writers, 0);
  EXPECT_EQ(seen.max_matched_readers, 0);
}

TEST_F(Security, AnUnsecuredParticipantSeesNothingAndChangesNothing) {
  if (!compiled_in("cyclone")) GTEST_SKIP() << "the outsider is a Cyclone DDS participant";
  run_plain();
  if (HasFatalFailure()) return;
  transport::DomainLock domain = transport::DomainLock::acquire();
  auto unsecured = transport::create_participant("cyclone", domain.domain_id(), std::nullopt);
  const pid_t launcher = spawn_secured(domain.domain_id());
  std::atomic<bool> stop{false};
  std::atomic<int> forged{0};
  OutsiderReport seen;
  std::thread outsider([&] { seen = act_as_outsider(*unsecured, stop, forged); });
  // `mechsim topic list` beside it once it steps: with the observer identity it sees the
  // run's topics, without one none of them (docs/security.md, 'Which tools get an identity').
  const bool stepping = wait_secured_past(0.1, launcher);
  const int forged_while_stepping = forged.load();
  const std::vector<std::string> list{kMechsim, "topic", "list", "--domain", std::to_string(domain.domain_id()), "--wait", "1.5"};
  ::setenv(transport::kSecurityDirEnv, sec().c_str(), 1);
  ::setenv(transport::kSecurityIdentityEnv, "observer", 1);
  const CommandResult observed = run(list, log("observer"), 30);
  ::unsetenv(transport::kSecurityDirEnv);
  ::unsetenv(transport::kSecurityIdentityEnv);
  const CommandResult unobserved = run(list, log("unsecured-list"), 30);
  // The run goes on until it is stopped: both lists saw the run, not its remains.
  const bool still_running = !has_exited(launcher);
  const bool past = stepping && still_running && wait_secured_past(1.0, launcher);
  const int forged_past = forged.load();
  stop_and_compare(launcher);
  stop = true;
  outsider.join();
  ASSERT_TRUE(stepping) << "the secured run ended before it stepped";
  EXPECT_TRUE(still_running) << "the run must still have been going while both listed";
  ASSERT_TRUE(past) << "the secured run ended before it was told to";
  EXPECT_NE(observed.output.find("servo/command"), std::string::npos) << observed.output;
  // Unsecured, it sees only the other unsecured participant here (the outsider's two
  // endpoints), none of the run's.
  EXPECT_EQ(unobserved.output.find("mechsim/control"), std::string::npos) << unobserved.output;
  EXPECT_EQ(unobserved.output.find("slide/state"), std::string::npos) << unobserved.output;
  EXPECT_NE(observed.output.find("mechsim/control"), std::string::npos) << observed.output;
  EXPECT_GT(forged_past, forged_while_stepping) << "the outsider must have written while the run went on";
  EXPECT_EQ(seen.samples_read, 0);
  EXPECT_EQ(seen.max_matched_writers, 0);
  EXPECT_EQ(seen.max_matched_readers, 0);
}

// A valid identity (the run's own "servo") is refused what its permissions do not grant:
// writing the slide's topic, reading the nodes' status. What it may do works (control case).
class Permissions : public Security, public ::testing::WithParamInterface<std::string> {};

TEST_P(Permissions, AValidParticipantIsRefusedTopicsItsPermissionsLack) {
  const std::string vendor = GetParam();
  if (!compiled_in(vendor)) GTEST_SKIP() << vendor << " is not in this build";
  transport::DomainLock domain = transport::DomainLock::acquire();
  auto servo = transport::create_participant(vendor, domain.domain_id(), transport::SecurityIdentity{sec(), "servo"});
  const transport::TopicType* command = transport::find_topic_type("ServoCommand");
  const transport::TopicType* slide = transport::find_topic_type("SlideState");
  ASSERT_NE(command, nullptr);
  ASSERT_NE(slide, nullptr);
  EXPECT_NO_THROW(servo->create_writer("servo/command", *command));
  EXPECT_NO_THROW(servo->create_reader("slide/state", *slide));
  try {
    servo->create_writer("slide/state", *slide);
    ADD_FAILURE() << "servo may not publish slide/state, but its writer was created";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("slide/state"), std::string::npos) << e.what();
  }
  EXPECT_THROW(servo->create_status_reader(), std::runtime_error) << "servo may not read mechsim/status";
  EXPECT_NO_THROW(servo->create_status_writer());
}

INSTANTIATE_TEST_SUITE_P(Vendors, Permissions, ::testing::Values("cyclone", "fastdds"),
                         [](const auto& info) { return info.param; });

// ---------------------------------------------------------------------------------------
// Cyclone DDS 0.10 <-> Fast DDS 2.9, secured: they interoperate only when Cyclone starts
// the PKI-DH handshake (docs/security.md 'Vendors'). Shown on the seam with the run's
// identities; the same pairs unsecured are the control that the set-up itself works. If a
// later vendor release fixes the handshake, the last expectation fails: then lift the
// launcher's refusal of mixed secured runs.

// A participant of each vendor, one with the identity `on_cyclone`, the other `on_fastdds`
// (servo and tacho, in either order), each writing its own topic (servo/command,
// tacho/state) every 10 ms and reading the other's: how many of the two directions
// delivered a sample within `timeout`.
int directions_across_vendors(const std::string& on_cyclone, const std::string& on_fastdds, bool secured, int domain,
                              std::chrono::seconds timeout) {
  const auto identity = [&](const std::string& name) {
    return secured ? std::optional<transport::SecurityIdentity>(transport::SecurityIdentity{Security::sec_dir(), name}) : std::nullopt;
  };
  auto cyclone = transport::create_participant("cyclone", domain, identity(on_cyclone));
  auto fast = transport::create_participant("fastdds", domain, identity(on_fastdds));
  const auto topic = [](const std::string& name) { return name == "servo" ? "servo/command" : "tacho/state"; };
  const auto type = [](const std::string& name) { return transport::find_topic_type(name == "servo" ? "ServoCommand" : "TachoState"); };
  auto cyclone_writer = cyclone->create_writer(topic(on_cyclone), *type(on_cyclone));
  auto fast_reader = fast->create_reader(topic(on_cyclone), *type(on_cyclone));
  auto fast_writer = fast->create_writer(topic(on_fastdds), *type(on_fastdds));
  auto cyclone_reader = cyclone->create_reader(topic(on_fastdds), *type(on_fastdds));
  std::vector<double> from_cyclone(type(on_cyclone)->fields.size(), 1.0), from_fast(type(on_fastdds)->fields.size(), 1.0);
  transport::SampleHeader h;
  std::vector<double> got;
  bool to_fast = false, to_cyclone = false;
  const auto end = std::chrono::steady_clock::now() + timeout;
  for (std::uint64_t k = 0; std::chrono::steady_clock::now() < end && !(to_fast && to_cyclone); ++k) {
    cyclone_writer->write({1, k, 0.0}, from_cyclone);
    fast_writer->write({1, k, 0.0}, from_fast);
    while (fast_reader->take(h, got)) to_fast = true;
    while (cyclone_reader->take(h, got)) to_cyclone = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return int(to_fast) + int(to_cyclone);
}

TEST_F(Security, CycloneAndFastDdsInteroperateSecuredOnlyWhenCycloneStartsTheHandshake) {
  if (!compiled_in("cyclone") || !compiled_in("fastdds")) GTEST_SKIP() << "needs both vendors";
  for (const auto& [on_cyclone, on_fastdds] : {std::pair{"servo", "tacho"}, std::pair{"tacho", "servo"}}) {
    transport::DomainLock domain = transport::DomainLock::acquire();
    EXPECT_EQ(directions_across_vendors(on_cyclone, on_fastdds, false, domain.domain_id(), std::chrono::seconds(10)), 2)
        << "unsecured, " << on_cyclone << " on Cyclone and " << on_fastdds << " on Fast DDS must talk both ways";
  }
  // Secured: a secured participant's GUID prefix is derived from its certificate's subject
  // (DDS Security 9.3.3), so which of the two starts the handshake is fixed by the pair of
  // identities, whatever the vendor. With servo on Cyclone, Cyclone starts it (ECDH) and
  // both directions work; with the vendors swapped, Fast DDS starts it with DH+MODP-2048,
  // whose public key Cyclone cannot decode ("Failed to convert octet sequence to ASN1
  // integer"): nothing arrives, either way.
  {
    transport::DomainLock domain = transport::DomainLock::acquire();
    EXPECT_EQ(directions_across_vendors("servo", "tacho", true, domain.domain_id(), std::chrono::seconds(10)), 2);
  }
  transport::DomainLock domain = transport::DomainLock::acquire();
  EXPECT_EQ(directions_across_vendors("tacho", "servo", true, domain.domain_id(), std::chrono::seconds(10)), 0);
}

// So the launcher refuses a secured mixed layout before anything starts, saying why.
TEST_F(Security, ASecuredMixedLayoutIsRefusedBeforeAnythingStarts) {
  const CommandResult r = run(run_args("mixed", "mixed", true), log("mixed"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("dds.security: expected one DDS vendor for the launcher and every participant"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("got cyclone for the launcher, tacho and fastdds for servo, slide"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "mixed")) << "nothing may start";
}

// ---------------------------------------------------------------------------------------
// The pieces without a run: permissions derived from the plan, one property builder.

// On every shipped scene with a connection: each participant may publish exactly its own
// topics (and status), and every topic it reads is one another participant may publish.
TEST(SecurityGrants, EveryInputIsPublishableByExactlyOneOtherParticipant) {
  int scenes = 0;
  for (const auto& e : fs::recursive_directory_iterator(MECHSIM_SOURCE_DIR "/config/scenes")) {
    if (e.path().extension() != ".yaml") continue;
    std::optional<cosim::ScenePlan> plan;
    config::Scene scene;
    try {
      scene = config::load_scene(e.path().string());
      plan.emplace(cosim::ScenePlan::build(scene));
    } catch (const config::ConfigError&) {
      continue;  // not a time-run scene (cvt_map.yaml)
    }
    ++scenes;
    const auto grants = security::grants_for_plan(*plan);
    ASSERT_EQ(grants.size(), plan->nodes().size() + 2) << e.path();
    for (const auto& node : plan->nodes()) {
      const auto& g = *std::find_if(grants.begin(), grants.end(), [&](const auto& x) { return x.name == node.name(); });
      for (const auto& topic : g.publish)
        EXPECT_TRUE(topic == transport::kStatusTopic || topic.rfind(node.name() + "/", 0) == 0)
            << e.path() << ": " << node.name() << " may publish " << topic;
      for (const auto& topic : g.subscribe) {
        if (topic == transport::kControlTopic) continue;
        int publishers = 0;
        for (const auto& other : grants)
          publishers += other.name != node.name() && std::count(other.publish.begin(), other.publish.end(), topic);
        EXPECT_EQ(publishers, 1) << e.path() << ": " << node.name() << " reads " << topic;
      }
    }
  }
  EXPECT_GT(scenes, 10);
}

// Both vendors get the same five files, each under its own property names.
TEST(SecurityProperties, BothVendorsGetTheSameFiles) {
  const fs::path dir = fs::temp_directory_path() / ("mechsim-security-props-" + std::to_string(::getpid()));
  fs::create_directories(dir / "servo");
  const transport::SecurityIdentity id{dir.string(), "servo"};
  for (const auto& f : id.files()) std::ofstream(f) << "x";
  ::chmod(id.private_key().c_str(), 0600);
  std::vector<std::string> files;
  for (const auto& f : id.files()) files.push_back("file://" + f);
  for (const char* vendor : {"cyclone", "fastdds"}) {
    std::set<std::string> uris;
    for (const auto& [name, value] : transport::security_properties(id, vendor)) {
      EXPECT_EQ(name.rfind("dds.sec.", 0), 0u) << name;
      if (value.rfind("file://", 0) == 0) uris.insert(value);
    }
    EXPECT_EQ(uris, std::set<std::string>(files.begin(), files.end())) << vendor;
  }
  ::chmod(id.private_key().c_str(), 0640);
  EXPECT_THROW(transport::security_properties(id, "cyclone"), std::runtime_error);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------
// Bad folders: refused before anything starts, naming the file and the key.

TEST_F(Security, AMissingOrIncompleteFolderIsRefusedNamingTheFile) {
  const std::string missing = (dir_ / "nowhere").string();
  CommandResult r = run(launch_args(kScene, "missing", {"--set", "dds.security=" + missing}), log("missing"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("dds.security: " + missing + "/ca.pem: missing"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mechsim security init"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "missing")) << "nothing may start";

  // A copy of the folder without the slide's certificate, and with a readable key.
  const fs::path partial = dir_ / "partial";
  fs::copy(sec(), partial, fs::copy_options::recursive);
  fs::remove(partial / "slide" / "cert.pem");
  ::chmod((partial / "tacho" / "key.pem").c_str(), 0644);
  r = run(launch_args(kScene, "partial", {"--set", "dds.security=" + partial.string()}), log("partial"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("dds.security: " + (partial / "slide" / "cert.pem").string() + ": missing (participant 'slide')"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find((partial / "tacho" / "key.pem").string() + ": a private key readable by others (mode 0644)"),
            std::string::npos)
      << r.output;
  // mechsim security init writes its keys 0600.
  struct stat st {};
  ASSERT_EQ(::stat((fs::path(sec()) / "servo" / "key.pem").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  ASSERT_EQ(::stat((fs::path(sec()) / "ca_key.pem").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
}

// Multi-host runs would need identities for the agents and the nodes they start: refused
// when the scene is loaded, naming the key.
TEST_F(Security, AMultiHostSceneWithSecurityIsRefused) {
  const fs::path scene = dir_ / "hosts.yaml";
  std::ofstream(scene) << "scene: secured_hosts\n"
                          "time: {start: 0 s, end: 0.01 s, step: 1 ms}\n"
                          "dds: {domain: 5, security: sec}\n"
                          "hosts:\n  a: {address: 10.0.0.2}\n"
                          "participants:\n  cam:\n    type: cam_shaft\n    host: a\n"
                          "    params: {speed: 60 rpm, pitch_radius: 50 mm, law: [{type: dwell, start: 0 deg, span: 360 deg, lift: 0 mm}]}\n";
  const CommandResult r = run({kMechsim, "check", scene.string()}, log("check"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(scene.string() + ": hosts: expected no hosts with dds.security"), std::string::npos) << r.output;
}

// ---------------------------------------------------------------------------------------
// dds.protection: sign (issue 31): authenticated, access-controlled, signed, not encrypted.
// Added in blocks of their own; the tests above are left as they are.

// The same bytes signed as unsecured, on each vendor; the launcher and the summary say which
// protection the run had.
class SignedRun : public Security, public ::testing::WithParamInterface<std::string> {};

TEST_P(SignedRun, NodeOutputsAreByteIdenticalToAnUnsecuredRun) {
  const std::string layout = GetParam();
  if (!compiled_in(layout)) GTEST_SKIP() << layout << " is not in this build";
  const CommandResult plain = run(run_args("plain", layout, false), log("plain"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  std::string tag = "signed";
  const CommandResult signed_run = run_secured(tag, layout, {"--set", "dds.protection=sign"});
  ASSERT_EQ(signed_run.exit_code, 0) << signed_run.output;
  EXPECT_NE(signed_run.output.find("DDS security: " + sec() + " (authentication, access control, signed, not encrypted"),
            std::string::npos)
      << signed_run.output;
  expect_identical_outputs("plain", tag);
  EXPECT_EQ(summary(tag)["dds_security"], sec());
  EXPECT_EQ(summary(tag)["dds_protection"], "sign");
}

INSTANTIATE_TEST_SUITE_P(Vendors, SignedRun, ::testing::Values("cyclone", "fastdds"),
                         [](const auto& info) { return info.param; });

// Signing leaves the samples readable on the wire, not open to participants: an unsecured
// participant, there from before the run starts until after it ended, writing forged
// servo/command samples, matches nothing and reads nothing, and the run ends ok and
// byte-identical (the same forgery fails an unsecured run: foreign_writer_test). One
// outsider per process: two Cyclone participants creating topics from two threads at once
// crash Cyclone DDS 0.10 (dds_create_topic_impl).
TEST_F(Security, ASignedRunAdmitsNoOutsider) {
  if (!compiled_in("cyclone")) GTEST_SKIP() << "the outsider is a Cyclone DDS participant";
  const CommandResult plain = run(run_args("plain", "cyclone", false, {"--end", "0.3 s"}), log("plain"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  transport::DomainLock domain = transport::DomainLock::acquire();
  auto unsecured = transport::create_participant("cyclone", domain.domain_id(), std::nullopt);
  std::atomic<bool> done{false};
  std::atomic<int> forged{0};
  OutsiderReport seen;
  // It acts before the launcher exists and until it has exited: alongside the whole run,
  // however fast this machine is.
  std::thread outsider([&] { seen = act_as_outsider(*unsecured, done, forged); });
  const CommandResult signed_run =
      run(run_args("signed", "cyclone", true,
                   {"--end", "0.3 s", "--set", "dds.protection=sign", "--set", "dds.domain=" + std::to_string(domain.domain_id())}),
          log("signed"), 120);
  done = true;
  outsider.join();
  ASSERT_EQ(signed_run.exit_code, 0) << signed_run.output;
  EXPECT_GT(forged.load(), 0) << "the outsider must have written during the run";
  EXPECT_EQ(seen.samples_read, 0);
  EXPECT_EQ(seen.max_matched_writers, 0);
  EXPECT_EQ(seen.max_matched_readers, 0);
  EXPECT_EQ(signed_run.output.find("foreign"), std::string::npos) << signed_run.output;
  expect_identical_outputs("plain", "signed");
}

// The two governance documents differ only in the protection kinds: four ENCRYPT (discovery,
// liveliness, submessages, payloads) and RTPS protection NONE, or three SIGN (discovery,
// liveliness, whole RTPS messages, which carry the submessages and payloads) and submessage
// and payload protection NONE; `security init` writes both, signed, and the domains read
// back from the signed files are 0..230.
TEST_F(Security, SecurityInitWritesAGovernancePerProtection) {
  const auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  const std::string encrypt = security::governance_xml("encrypt"), sign = security::governance_xml("sign");
  EXPECT_EQ(count(encrypt, ">ENCRYPT<"), 4u) << encrypt;
  EXPECT_EQ(count(encrypt, ">SIGN<"), 0u) << encrypt;
  EXPECT_EQ(count(encrypt, "<rtps_protection_kind>NONE<"), 1u) << encrypt;
  EXPECT_EQ(count(sign, ">SIGN<"), 3u) << sign;
  EXPECT_EQ(count(sign, "<rtps_protection_kind>SIGN<"), 1u) << sign;
  EXPECT_EQ(count(sign, "<metadata_protection_kind>NONE<"), 1u) << sign;
  EXPECT_EQ(count(sign, "<data_protection_kind>NONE<"), 1u) << sign;
  EXPECT_EQ(count(sign, "ENCRYPT"), 0u) << sign;
  EXPECT_THROW(security::governance_xml("none"), std::invalid_argument);
  for (const char* protection : {"encrypt", "sign"}) {
    const std::string file = transport::SecurityIdentity::governance_file(sec(), protection);
    const std::string p7s = slurp(file);
    EXPECT_NE(p7s.find("application/x-pkcs7-signature"), std::string::npos) << file;
    EXPECT_NE(p7s.find(protection == std::string("sign") ? "<rtps_protection_kind>SIGN<" : "<data_protection_kind>ENCRYPT<"),
              std::string::npos)
        << file;
    EXPECT_EQ(transport::describe(transport::governance_domains(file)), "0..230") << file;
  }
}

// Issue 31, item 4: a secured scene on a domain its governance does not cover is refused by
// `mechsim check` and `mechsim launch` before anything starts, naming the domain and the
// range read from the folder's governance (the one of the scene's protection).
TEST_F(Security, ADomainOutsideTheGovernanceIsRefusedBeforeAnythingStarts) {
  for (const char* protection : {"encrypt", "sign"}) {
    const std::vector<std::string> set{"--set", "dds.security=" + sec(), "--set", std::string("dds.protection=") + protection,
                                       "--set", "dds.domain=232"};
    const std::string governance = transport::SecurityIdentity::governance_file(sec(), protection);
    const std::string expected = "dds.domain: 232 is not a domain the governance covers (0..230, read from " + governance + ")";
    std::vector<std::string> check{kMechsim, "check", kScene};
    check.insert(check.end(), set.begin(), set.end());
    const CommandResult c = run(check, log(std::string("check-") + protection), 30);
    EXPECT_EQ(c.exit_code, 2) << c.output;
    EXPECT_NE(c.output.find(kScene + ": " + expected), std::string::npos) << c.output;
    const std::string tag = std::string("outside-") + protection;
    const CommandResult l = run(launch_args(kScene, tag, set), log(tag), 30);
    EXPECT_EQ(l.exit_code, 2) << l.output;
    EXPECT_NE(l.output.find(expected), std::string::npos) << l.output;
    EXPECT_EQ(l.output.find("It is not allowed to create participant"), std::string::npos) << l.output;
    EXPECT_FALSE(fs::exists(dir_ / tag)) << "nothing may start";
  }
  // 230, the last domain covered, passes the check (a control: the refusal is the range's).
  const CommandResult inside =
      run({kMechsim, "check", kScene, "--set", "dds.security=" + sec(), "--set", "dds.domain=230"}, log("check-230"), 30);
  EXPECT_EQ(inside.exit_code, 0) << inside.output;

  // The range is read from the folder, not assumed: a governance re-signed by the CA for
  // domains 5..9 refuses 12, and a scene without dds.domain (the launcher picks in 1..230).
  const fs::path narrow = dir_ / "narrow";
  fs::copy(sec(), narrow, fs::copy_options::recursive);
  std::string xml = slurp((narrow / "governance.xml").string());
  const std::string all = "<min>0</min><max>230</max>";
  ASSERT_NE(xml.find(all), std::string::npos) << xml;
  xml.replace(xml.find(all), all.size(), "<min>5</min><max>9</max>");
  std::ofstream(narrow / "governance.xml") << xml;
  ASSERT_EQ(std::system(("openssl smime -sign -text -in " + (narrow / "governance.xml").string() + " -out " +
                         (narrow / "governance.p7s").string() + " -signer " + (narrow / "ca.pem").string() + " -inkey " +
                         (narrow / "ca_key.pem").string())
                            .c_str()),
            0);
  const CommandResult twelve =
      run({kMechsim, "check", kScene, "--set", "dds.security=" + narrow.string(), "--set", "dds.domain=12"}, log("narrow-12"), 30);
  EXPECT_EQ(twelve.exit_code, 2) << twelve.output;
  EXPECT_NE(twelve.output.find("dds.domain: 12 is not a domain the governance covers (5..9, read from " +
                               (narrow / "governance.p7s").string() + "); expected a domain in 5..9"),
            std::string::npos)
      << twelve.output;
  const CommandResult picked = run({kMechsim, "check", kScene, "--set", "dds.security=" + narrow.string()}, log("narrow-auto"), 30);
  EXPECT_EQ(picked.exit_code, 2) << picked.output;
  EXPECT_NE(picked.output.find("covers domains 5..9, not every domain the launcher may pick (in 1..230, e.g. 1); expected "
                               "dds.domain fixed to one of 5..9"),
            std::string::npos)
      << picked.output;
  const CommandResult seven =
      run({kMechsim, "check", kScene, "--set", "dds.security=" + narrow.string(), "--set", "dds.domain=7"}, log("narrow-7"), 30);
  EXPECT_EQ(seven.exit_code, 0) << seven.output;
}

// dds.protection is a choice of two, and only for a secured scene: refused when loaded.
TEST_F(Security, AProtectionWithoutSecurityOrOfAnotherKindIsRefused) {
  const CommandResult alone = run({kMechsim, "check", kScene, "--set", "dds.protection=sign"}, log("alone"), 30);
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(alone.output.find("dds.protection: expected dds.security with it"), std::string::npos) << alone.output;
  const CommandResult other_kind =
      run({kMechsim, "check", kScene, "--set", "dds.security=" + sec(), "--set", "dds.protection=none"}, log("none"), 30);
  EXPECT_EQ(other_kind.exit_code, 2) << other_kind.output;
  EXPECT_NE(other_kind.output.find("dds.protection"), std::string::npos) << other_kind.output;
  EXPECT_NE(other_kind.output.find("sign"), std::string::npos) << other_kind.output;
}

}  // namespace
}  // namespace mechsim::testing
