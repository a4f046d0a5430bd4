// Every class of bad scene input is refused before anything runs, with a message that
// names the file, the key path and what was expected.
#include <gtest/gtest.h>

#include "mechsim/cosim/scene_plan.h"
#include "scene_files.h"

namespace mechsim::cosim {
namespace {

using testing::cam_press_with;
using testing::write_scene;

// Loads and plans a scene; returns the refusal message ("" when accepted).
std::string refusal(const std::string& text, std::string* path_out = nullptr) {
  const std::string path = write_scene(text);
  if (path_out) *path_out = path;
  try {
    config::Scene scene = config::load_scene(path);
    ScenePlan::build(scene);
    return "";
  } catch (const config::ConfigError& e) {
    return e.what();
  }
}

void expect_refused(const std::string& text, const std::string& key_path, const std::string& expected_words) {
  std::string path;
  std::string msg = refusal(text, &path);
  ASSERT_FALSE(msg.empty()) << "accepted, but should refuse at " << key_path;
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find(key_path), std::string::npos) << msg;
  EXPECT_NE(msg.find(expected_words), std::string::npos) << msg;
}

TEST(SceneValidation, TheShippedCamPressIsAccepted) {
  EXPECT_EQ(refusal(testing::read_file(testing::shipped_scene("cam_press.yaml"))), "");
}

// Settings parsed once into enums and timings (nothing downstream compares their words).
TEST(SceneValidation, ModeOverrunAndFaultTimingsAreParsedOnce) {
  const std::string shipped = testing::shipped_scene("nc_slide_loop.yaml");
  const config::Scene plain = config::load_scene(shipped);
  EXPECT_EQ(plain.mode, config::RunMode::lockstep);
  EXPECT_EQ(plain.realtime.on_overrun, config::OverrunPolicy::keep_going);
  const config::Scene rt = config::load_scene(shipped, {"mode=realtime", "realtime.on_overrun=abort", "faults.partition_grace=6 s"});
  EXPECT_EQ(rt.mode, config::RunMode::realtime);
  EXPECT_EQ(rt.realtime.on_overrun, config::OverrunPolicy::abort);
  EXPECT_STREQ(config::to_string(rt.mode), "realtime");
  EXPECT_STREQ(config::to_string(rt.realtime.on_overrun), "abort");
  // docs/faults.md, 'Cut links': warning at grace / 2, lease grace + 3 s, agent grace + 1 s.
  const config::FaultTimings t = config::fault_timings(rt);
  EXPECT_EQ(t.partition_grace, 6.0);
  EXPECT_EQ(t.silence_warning, 3.0);
  EXPECT_EQ(t.dds_lease, 9.0);
  EXPECT_EQ(t.agent_timeout, 7.0);
  // The participants' test seams are read from the scene, and only the known ones.
  const config::Scene seams = config::load_scene(shipped, {"participants.tacho.testing.lose_writes_after_resume=true",
                                                           "participants.slide.testing.checkpoint_pause_step=300",
                                                           "participants.slide.testing.checkpoint_pause=3 s"});
  EXPECT_TRUE(seams.find_participant("tacho")->lose_writes_after_resume);
  EXPECT_FALSE(seams.find_participant("slide")->lose_writes_after_resume);
  EXPECT_EQ(seams.find_participant("slide")->checkpoint_pause_step, std::optional<std::uint64_t>(300));
  EXPECT_EQ(seams.find_participant("slide")->checkpoint_pause, 3.0);
  EXPECT_THROW(config::load_scene(shipped, {"participants.tacho.testing.lose_everything=true"}), config::ConfigError);
}

// `fields:` restricts what a connection carries (line shafts, docs/line-shaft.md): a field
// the subscriber does not read, or not a list, is refused naming the key.
TEST(SceneValidation, ConnectionFields) {
  const std::string from = "{from: cam, to: follower, order: gauss_seidel}";
  EXPECT_EQ(refusal(cam_press_with(from, "{from: cam, to: follower, order: gauss_seidel, fields: [angle, speed, lift, lift_d1, lift_d2, pressure_angle]}")), "");
  expect_refused(cam_press_with(from, "{from: cam, to: follower, order: gauss_seidel, fields: [angel]}"), "connections[0].fields",
                 "got 'angel'");
  expect_refused(cam_press_with(from, "{from: cam, to: follower, order: gauss_seidel, fields: angle}"), "connections[0].fields",
                 "expected a list");
  // The pressure angle only: the follower's other required inputs are left unfed.
  EXPECT_NE(refusal(cam_press_with(from, "{from: cam, to: follower, order: gauss_seidel, fields: [pressure_angle]}")), "");
}

TEST(SceneValidation, UnknownKeys) {
  expect_refused(cam_press_with("mass: 25 kg", "masss: 25 kg"), "participants.follower.params", "unknown key 'masss'");
  expect_refused(cam_press_with("mode: lockstep", "mood: lockstep"), "mood", "unknown key");
}

TEST(SceneValidation, MissingKeys) {
  expect_refused(cam_press_with("mass: 25 kg", ""), "participants.follower.params.mass", "missing");
  expect_refused(cam_press_with("    type: follower", ""), "participants.follower.type", "missing");
}

TEST(SceneValidation, WrongUnits) {
  expect_refused(cam_press_with("mass: 25 kg", "mass: 25 mm"), "participants.follower.params.mass", "mass");
  expect_refused(cam_press_with("speed: 30 rpm", "speed: 30 mm"), "participants.cam.params.speed", "angular");
  expect_refused(cam_press_with("step: 1 ms", "step: 1 furlong"), "time.step", "");
}

TEST(SceneValidation, NonPhysicalValues) {
  expect_refused(cam_press_with("mass: 25 kg", "mass: -25 kg"), "participants.follower.params.mass", "");
  expect_refused(cam_press_with("mass: 25 kg", "mass: 0 kg"), "participants.follower.params.mass", "");
  expect_refused(cam_press_with("step: 1 ms", "step: 0 ms"), "time.step", "");
  expect_refused(cam_press_with("end: 2 s", "end: 0 s"), "time.end", "after the start");
  expect_refused(cam_press_with("end: 2 s", "end: 2.0005 s"), "time.end", "whole number of steps");
}

TEST(SceneValidation, OverlappingFollowerLoads) {
  expect_refused(cam_press_with("{from: 100 deg, to: 120 deg", "{from: 99 deg, to: 120 deg"),
                 "participants.follower.params.loads", "overlaps [45.000000, 100.000000) deg");
}

// What a model's own parameter check refuses (here a load beyond one revolution, which the
// parser lets through) is the scene's error at the participant's params, not an exception
// of another kind (tests/fuzz/scene_fuzz found the process ending on one).
TEST(SceneValidation, AModelsOwnParameterCheckNamesTheParticipant) {
  expect_refused(cam_press_with("{from: 180 deg, to: 210 deg", "{from: 180 deg, to: 400 deg"),
                 "participants.follower.params", "0 <= start < end <= 360");
}

TEST(SceneValidation, UnknownNodeType) {
  expect_refused(cam_press_with("type: follower", "type: folower"), "participants.follower.type", "node type");
}

TEST(SceneValidation, ConnectionsBetweenTypesThatCannotTalkOrToNobody) {
  expect_refused(cam_press_with("{from: cam, to: follower, order: gauss_seidel}", "{from: cam, to: nobody}"),
                 "connections[0].to", "participant");
  // Without the cam -> follower connection the follower's required inputs are unfed.
  expect_refused(cam_press_with("  - {from: cam, to: follower, order: gauss_seidel}\n", ""), "connections",
                 "required input");
}

TEST(SceneValidation, CyclesOfGaussSeidelEdgesAreRefusedAndNamed) {
  std::string msg = refusal(cam_press_with("order: jacobi, reconstruction: hold", "order: gauss_seidel"));
  EXPECT_NE(msg.find("Gauss-Seidel edges without cycles"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cam -> follower"), std::string::npos) << msg;
}

TEST(SceneValidation, AMotionLawThatDoesNotCloseIsRefused) {
  expect_refused(cam_press_with("lift: -25 mm", "lift: -20 mm"), "participants.cam.params.law", "does not close");
}

TEST(SceneValidation, OverridesAreValidatedLikeTheFile) {
  const std::string path = write_scene(testing::read_file(testing::shipped_scene("cam_press.yaml")));
  EXPECT_THROW(config::load_scene(path, {"time.step=-1 ms"}), config::ConfigError);
  config::Scene ok = config::load_scene(path, {"participants.cam.params.speed=60 rpm", "time.end=1 s"});
  EXPECT_EQ(ok.time.steps(), 1000);
}

TEST(SceneValidation, RecordSection) {
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: {fil: x.mcap}"), "record", "unknown key 'fil'");
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: {compression: gzip}"), "record.compression", "zstd");
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: {regex: '(cam'}"), "record.regex", "regular expression");
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: {topics: [a], regex: a}"), "record.regex", "not both");
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: maybe"), "record", "");

  auto load = [](const std::string& text) { return config::load_scene(write_scene(text)); };
  EXPECT_FALSE(load(cam_press_with("mode: lockstep", "mode: lockstep")).record.has_value());
  EXPECT_FALSE(load(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: false")).record.has_value());
  const auto all = load(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: true")).record;
  ASSERT_TRUE(all.has_value());
  EXPECT_EQ(all->file, "recording.mcap");
  EXPECT_TRUE(all->topics.empty() && all->regex.empty());
  EXPECT_EQ(all->compression, "zstd");
  const auto some =
      load(cam_press_with("mode: lockstep", "mode: lockstep\nrecord: {file: a.mcap, topics: [cam/state], compression: lz4}")).record;
  ASSERT_TRUE(some.has_value());
  EXPECT_EQ(some->file, "a.mcap");
  EXPECT_EQ(some->topics, std::vector<std::string>{"cam/state"});
  EXPECT_EQ(some->compression, "lz4");
  // --set record=true on a scene without the section, as the launcher's users write it.
  const std::string path = write_scene(cam_press_with("mode: lockstep", "mode: lockstep"));
  EXPECT_TRUE(config::load_scene(path, {"record=true"}).record.has_value());
}


// Multi-host scenes (docs/hosts.md): hosts are checked like every other key.
TEST(SceneValidation, HostsAndPlacement) {
  const std::string hosts = "mode: lockstep\ndds: {domain: 17}\nhosts:\n  a: {address: 10.0.0.1}\n  b: {address: rt-box.plant.lan}\n";
  const std::string placed = "    type: follower\n    host: b";
  std::string ok = cam_press_with("mode: lockstep", hosts);
  ok.replace(ok.find("    type: follower"), std::string("    type: follower").size(), placed);
  EXPECT_EQ(refusal(ok), "");
  {
    config::Scene scene = config::load_scene(write_scene(ok));
    ASSERT_EQ(scene.hosts.size(), 2u);
    EXPECT_EQ(scene.hosts[1].address, "rt-box.plant.lan");
    EXPECT_EQ(scene.find_participant("follower")->host, "b");
    EXPECT_EQ(scene.find_participant("cam")->host, "");
  }
  std::string unknown = ok;
  unknown.replace(unknown.find("host: b"), 7, "host: c");
  expect_refused(unknown, "participants.follower.host", "expected a host of the scene's hosts: section (a, b), got 'c'");
  std::string no_domain = ok;
  no_domain.replace(no_domain.find("dds: {domain: 17}"), 17, "");
  expect_refused(no_domain, "participants.follower.host", "set dds.domain");
  expect_refused(cam_press_with("mode: lockstep", "hosts:\n  a: {address: 10.0.0.1/24}\n"), "hosts.a.address", "expected an IPv4 address");
  expect_refused(cam_press_with("mode: lockstep", "hosts:\n  a: {adress: 10.0.0.1}\n"), "hosts.a", "unknown key 'adress'");
  expect_refused(cam_press_with("mode: lockstep", "hosts:\n  a: {address: 10.0.0.1}\n  b: {address: 10.0.0.1}\n"), "hosts.b.address",
                 "expected each host once");
}

}  // namespace
}  // namespace mechsim::cosim

namespace mechsim::cosim {
namespace {

// Restart with rollback (docs/faults.md): the keys, and what it is not built for.
TEST(SceneValidation, RestartKeys) {
  const std::string on = "mode: lockstep\nfaults: {restart: on_failure, restart_limit: 2, checkpoint_every: 250}";
  const config::Scene scene = config::load_scene(write_scene(cam_press_with("mode: lockstep", on)));
  EXPECT_TRUE(scene.checkpointing());
  EXPECT_EQ(scene.faults.restart_limit, 2);
  EXPECT_EQ(scene.faults.checkpoint_every, 250);
  EXPECT_TRUE(scene.find_participant("cam")->restart);
  // A participant's own restart: overrides the scene's.
  const config::Scene one = config::load_scene(write_scene(cam_press_with("    type: follower", "    type: follower\n    restart: on_failure")));
  EXPECT_TRUE(one.checkpointing());
  EXPECT_TRUE(one.find_participant("follower")->restart);
  EXPECT_FALSE(one.find_participant("cam")->restart);
  EXPECT_FALSE(config::load_scene(testing::shipped_scene("cam_press.yaml")).checkpointing());
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nfaults: {restart: always}"), "faults.restart", "on_failure");
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nfaults: {restart_limit: 0}"), "faults.restart_limit", ">= 1");
  expect_refused(cam_press_with("mode: lockstep", "mode: lockstep\nfaults: {checkpoint_every: 0}"), "faults.checkpoint_every", ">= 1");
  expect_refused(cam_press_with("mode: lockstep", "mode: realtime\nfaults: {restart: on_failure}"), "faults.restart", "lockstep only");
  // Any participant on another host: the launcher could not find its checkpoints.
  std::string hosts = cam_press_with("mode: lockstep", "mode: lockstep\ndds: {domain: 5}\nhosts: {b: {address: 10.0.0.2}}\n"
                                                       "faults: {restart: on_failure}");
  hosts.replace(hosts.find("    type: follower"), 18, "    type: follower\n    host: b\n    restart: never");
  expect_refused(hosts, "participants.follower.host", "launcher's host only");
}

// Participants sharing a process (`process: <group>`, docs/scenes.md): what belongs to a
// process must fit all of its members.
TEST(SceneValidation, ProcessGroups) {
  auto grouped = [](const std::string& cam_extra, const std::string& follower_extra, const std::string& scene_extra = "") {
    std::string text = cam_press_with("mode: lockstep", "mode: lockstep" + scene_extra);
    text.replace(text.find("    type: cam_shaft"), 19, "    type: cam_shaft\n    process: press" + cam_extra);
    text.replace(text.find("    type: follower"), 18, "    type: follower\n    process: press" + follower_extra);
    return text;
  };
  const config::Scene scene = config::load_scene(write_scene(grouped("", "")));
  EXPECT_EQ(scene.find_participant("cam")->process, "press");
  EXPECT_EQ(scene.find_participant("follower")->process, "press");
  EXPECT_EQ(config::load_scene(testing::shipped_scene("cam_press.yaml")).find_participant("cam")->process, "");
  expect_refused(grouped("", "").replace(grouped("", "").find("process: press"), 14, "process: a-b"), "participants.cam.process",
                 "letters, digits and '_'");
  // A crash takes the whole process: its members restart together or not at all.
  expect_refused(grouped("", "\n    restart: on_failure"), "participants.follower.process", "restart together");
  // Real-time settings are the process's.
  expect_refused(grouped("", "\n    realtime: {priority: 10}"), "participants.follower.process", "whole process");
  // One process runs on one host; a group on another host is one process its agent starts.
  expect_refused(grouped("", "\n    host: b", "\ndds: {domain: 5}\nhosts: {b: {address: 10.0.0.2}}"), "participants.follower.process",
                 "'cam' is on the launcher's host, 'follower' on host 'b'");
  EXPECT_EQ(refusal(grouped("\n    host: b", "\n    host: b", "\ndds: {domain: 5}\nhosts: {b: {address: 10.0.0.2}}"), nullptr), "");
}

// `processes:` (docs/scenes.md): per_participant, per_core or a number of groups per vendor.
TEST(SceneValidation, ProcessLayout) {
  auto with = [](const std::string& value) { return cam_press_with("mode: lockstep", "mode: lockstep\nprocesses: " + value); };
  EXPECT_EQ(config::load_scene(testing::shipped_scene("cam_press.yaml")).processes.kind, config::ProcessLayout::Kind::automatic);
  EXPECT_EQ(config::load_scene(write_scene(with("auto"))).processes.kind, config::ProcessLayout::Kind::automatic);
  EXPECT_EQ(config::load_scene(write_scene(with("per_participant"))).processes.kind, config::ProcessLayout::Kind::per_participant);
  EXPECT_EQ(config::load_scene(write_scene(with("per_core"))).processes.kind, config::ProcessLayout::Kind::per_core);
  const config::Scene three = config::load_scene(write_scene(with("3")));
  EXPECT_EQ(three.processes.kind, config::ProcessLayout::Kind::count);
  EXPECT_EQ(three.processes.count, 3);
  for (const char* bad : {"per_cor", "0", "65", "-1", "2.5", "[1]"})
    expect_refused(with(bad), "processes", "auto, per_participant, per_core or a number of process groups per DDS vendor (1..64)");
  // Groups carry no per-participant identity.
  expect_refused(with("per_core\ndds: {security: /tmp/no-such-folder}"), "processes", "not available with dds.security");
}

}  // namespace
}  // namespace mechsim::cosim

namespace mechsim::cosim {
namespace {

// time.step: adaptive (docs/accuracy.md "Adaptive macro step").
std::string adaptive(const std::string& keys) {
  return cam_press_with("time: {start: 0 s, end: 2 s, step: 1 ms}", "time: {start: 0 s, end: 2 s, step: adaptive" + keys + "}");
}

TEST(SceneValidation, AdaptiveStep) {
  EXPECT_EQ(refusal(adaptive(", tolerance: 1e-3, min: 1 us, max: 5 ms, scales: {follower: {drive_torque_rest: 20 N m}}"), nullptr), "");
  expect_refused(adaptive(", tolerance: 2"), "time.tolerance", "(0, 1)");
  expect_refused(adaptive(", min: 2 ms, max: 1 ms"), "time.min", "min <= max");
  expect_refused(adaptive(", max: 3 s"), "time.max", "end - start");
  expect_refused(adaptive(", min: 1 ns"), "time.min", "1e8 steps");
  std::string far = adaptive(", min: 1 ns, max: 1 ns");
  far.replace(far.find("start: 0 s, end: 2 s"), std::string("start: 0 s, end: 2 s").size(), "start: 1e9 s, end: 1.0000000000001e9 s");
  expect_refused(far, "time.min", "double precision");
  expect_refused(adaptive(", initial: 1 s, max: 1 ms"), "time.initial", "between min and max");
  expect_refused(adaptive(", tolerance: 1e-3, stepp: 1"), "time", "unknown key 'stepp'");
  expect_refused(adaptive(", scales: {press: {drive_torque_rest: 20 N m}}"), "time.scales.press", "participant of this scene");
  expect_refused(adaptive(", scales: {follower: {torque: 20 N m}}"), "time.scales.follower.torque", "FollowerState");
  expect_refused(adaptive(", scales: {follower: {drive_torque_rest: -1 N m}}"), "time.scales.follower.drive_torque_rest", "positive");
  // A fixed period (real time) and checkpoints of a step index (restart) need a fixed step.
  std::string rt = adaptive("");
  rt.replace(rt.find("mode: lockstep"), std::string("mode: lockstep").size(), "mode: realtime");
  expect_refused(rt, "mode", "adaptive");
  expect_refused(adaptive("") + "\nfaults: {restart: on_failure}\n", "faults.restart", "adaptive");
}

// Under an adaptive step a node solver's tolerance follows the coupling tolerance where the
// scene writes none (rtol = min(1e-6, tolerance x 1e-4), atol = rtol / 1000); a written one
// stands, and a fixed step keeps the defaults.
TEST(SceneValidation, NodeSolverTolerancesFollowTheAdaptiveTolerance) {
  const auto follower_solver = [](const std::string& text) {
    const config::Scene scene = config::load_scene(write_scene(text));
    return scene.find_participant("follower")->solver;
  };
  config::SolverSpec s = follower_solver(adaptive(", tolerance: 1e-4"));
  EXPECT_DOUBLE_EQ(s.rtol, 1e-8);
  EXPECT_DOUBLE_EQ(s.atol, 1e-11);
  s = follower_solver(adaptive(", tolerance: 5e-2"));
  EXPECT_DOUBLE_EQ(s.rtol, 1e-6) << "never looser than the default";
  EXPECT_DOUBLE_EQ(s.atol, 1e-9);
  std::string written = adaptive(", tolerance: 1e-4");
  written.replace(written.find("type: follower"), std::string("type: follower").size(),
                  "type: follower\n    solver: {rtol: 1e-7}");
  s = follower_solver(written);
  EXPECT_DOUBLE_EQ(s.rtol, 1e-7);
  EXPECT_DOUBLE_EQ(s.atol, 1e-10) << "atol follows the written rtol";
  s = follower_solver(cam_press_with("time: {start: 0 s, end: 2 s, step: 1 ms}", "time: {start: 0 s, end: 2 s, step: 1 ms}"));
  EXPECT_DOUBLE_EQ(s.rtol, 1e-6);
  EXPECT_DOUBLE_EQ(s.atol, 1e-9);
}

}  // namespace
}  // namespace mechsim::cosim
