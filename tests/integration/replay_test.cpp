// Recording a run from its scene (`record:`), standing in for a participant with the
// recording (`mechsim launch --replay`), and playing a recording again (`mechsim play`),
// over loopback DDS with real processes.
//
// What must hold: the launcher's recording holds every published sample of every data
// topic (the summary compares the counts); a run whose amplifier is replayed from that
// recording gives the live nodes' outputs bit for bit, even when the replayed amplifier's
// own parameters were changed (so it is the recording that drives them); and a recording
// played and recorded again gives the same CDR bytes per topic and step.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "mechsim/transport/domain_lock.h"
#include "mechsim/record/mcap_reader.h"
#include "cdr_decoder.h"
#include "player.h"
#include "recorder.h"
#include "run_fixture.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class ReplayTest : public RunFolderTest {};

// Topic -> (step -> CDR bytes) of every data topic in a recording.
std::map<std::string, std::map<std::uint64_t, std::vector<std::byte>>> data_samples(const std::string& file) {
  record::McapReader reader(file);
  std::map<std::string, std::map<std::uint64_t, std::vector<std::byte>>> out;
  reader.for_each_message([&](const record::MessageView& m) {
    const std::string& topic = reader.channels().at(m.channel_id).topic;
    if (topic.rfind("mechsim/", 0) == 0) return;
    out[topic][recorder::decode_header(m.data).step] = {m.data.begin(), m.data.end()};
  });
  return out;
}

constexpr std::uint64_t kNcSteps = 2000;  // 50 ms at 25 us

TEST_F(ReplayTest, ReplayedAmplifierDrivesTheLiveNodesBitForBit) {
  const std::vector<std::string> short_run{"--end", "50 ms"};
  auto args = short_run;
  args.insert(args.end(), {"--set", "record=true"});
  auto original = run(launch_args(scene_path("nc_slide_loop.yaml"), "original", args), log("original"), 180);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const json s = summary("original");
  ASSERT_TRUE(s.contains("recording")) << s.dump(2);
  EXPECT_TRUE(s["recording"]["complete"].get<bool>()) << s["recording"].dump(2);
  int data_topics = 0;
  for (const auto& t : s["recording"]["topics"])
    if (t.contains("published")) {
      ++data_topics;
      EXPECT_EQ(t["published"].get<std::uint64_t>(), kNcSteps + 1) << t.dump();
      EXPECT_EQ(t["recorded"].get<std::uint64_t>(), kNcSteps + 1) << t.dump();
    }
  EXPECT_EQ(data_topics, 3);
  const fs::path original_dir = run_folder("original");
  const std::string recording = (original_dir / "recording.mcap").string();
  ASSERT_TRUE(fs::exists(recording));

  // The amplifier replayed, with a setpoint twice as large: were it computed, the slide
  // would move twice as far. The recording rules, so the live nodes repeat the original.
  args = short_run;
  args.insert(args.end(), {"--replay", "servo=" + recording, "--set", "participants.servo.params.setpoint.distance=0.2 mm"});
  auto replayed = run(launch_args(scene_path("nc_slide_loop.yaml"), "replayed", args), log("replayed"), 180);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  EXPECT_EQ(summary("replayed")["replayed"]["servo"], recording);
  const fs::path replayed_dir = run_folder("replayed");
  for (const char* node : {"tacho", "slide"}) {
    SCOPED_TRACE(node);
    const std::string a = slurp((original_dir / (std::string(node) + ".outputs.bin")).string());
    const std::string b = slurp((replayed_dir / (std::string(node) + ".outputs.bin")).string());
    EXPECT_GT(a.size(), kNcSteps * 8);
    EXPECT_TRUE(a == b) << "outputs of the live node differ from the original run";
  }

  // Control: the same changed scene computed live does move the slide differently.
  args = short_run;
  args.insert(args.end(), {"--set", "participants.servo.params.setpoint.distance=0.2 mm"});
  auto live = run(launch_args(scene_path("nc_slide_loop.yaml"), "live", args), log("live"), 180);
  ASSERT_EQ(live.exit_code, 0) << live.output;
  EXPECT_NE(slurp((original_dir / "slide.outputs.bin").string()), slurp((run_folder("live") / "slide.outputs.bin").string()));
}

// An adaptive macro step: the replayed amplifier proposes the recorded run's instants, so
// the live nodes step where they stepped and repeat their outputs bit for bit.
// The live nodes of a replayed run logged the original run's bytes (`steps` rows at least).
void expect_live_nodes_repeat(const fs::path& original_dir, const fs::path& replayed_dir, const std::vector<std::string>& nodes,
                              std::uint64_t steps) {
  for (const auto& node : nodes) {
    SCOPED_TRACE(node);
    const std::string a = slurp((original_dir / (node + ".outputs.bin")).string());
    const std::string b = slurp((replayed_dir / (node + ".outputs.bin")).string());
    EXPECT_GT(a.size(), steps * 8);
    EXPECT_TRUE(a == b) << "outputs of the live node differ from the original run";
  }
}

TEST_F(ReplayTest, AReplayOfAnAdaptiveRunStepsWhereTheRunStepped) {
  const std::vector<std::string> adaptive{"--end", "20 ms", "--set", "time.step=adaptive", "--set", "time.tolerance=1e-3",
                                          "--set", "time.max=25 us", "--set", "time.min=0.1 us"};
  auto args = adaptive;
  args.insert(args.end(), {"--set", "record=true"});
  auto original = run(launch_args(scene_path("nc_slide_loop.yaml"), "original", args), log("original"), 180);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const json s = summary("original");
  EXPECT_TRUE(s["recording"]["complete"].get<bool>()) << s["recording"].dump(2);
  const auto steps = s["steps"].get<std::uint64_t>();
  // The recording holds each node's step proposals too (one per step but the last).
  bool proposals = false;
  for (const auto& t : s["recording"]["topics"])
    if (t["topic"] == "servo/step") proposals = t["recorded"].get<std::uint64_t>() + 1 == steps;
  EXPECT_TRUE(proposals) << s["recording"]["topics"].dump(2);
  EXPECT_GT(s["adaptive_step"]["longest_s"].get<double>(), 1.5 * s["adaptive_step"]["shortest_s"].get<double>())
      << "the step did not vary: " << s["adaptive_step"].dump();
  // Without time.scales the launcher hands back this run's ranges of what the estimate scales
  // (the servo reads the tacho voltage and the slide's angle), to write in the scene.
  const json& suggested = s["adaptive_step"]["suggested_scales"];
  ASSERT_TRUE(suggested.contains("tacho") && suggested.contains("slide")) << s["adaptive_step"].dump(2);
  for (const auto& [participant, fields] : suggested.items())
    for (const auto& [field, range] : fields.items()) EXPECT_GT(range.get<double>(), 0.0) << participant << "." << field;
  EXPECT_NE(original.output.find("    scales: {"), std::string::npos) << original.output;
  const fs::path original_dir = run_folder("original");
  const std::string recording = (original_dir / "recording.mcap").string();

  args = adaptive;
  args.insert(args.end(), {"--replay", "servo=" + recording, "--set", "participants.servo.params.setpoint.distance=0.2 mm"});
  auto replayed = run(launch_args(scene_path("nc_slide_loop.yaml"), "replayed", args), log("replayed"), 180);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  EXPECT_EQ(summary("replayed")["steps"].get<std::uint64_t>(), steps);
  expect_live_nodes_repeat(original_dir, run_folder("replayed"), {"tacho", "slide"}, steps);
}

// The press line's cam is driven through the CVT: its law's joints and the follower's load
// boundaries are predicted at run time from the shaft's motion (docs/accuracy.md, "Events").
// The replayed cam predicts them from its recorded outputs, so the live nodes restart where
// they restarted and repeat their outputs bit for bit.
TEST_F(ReplayTest, AReplayedCamWhoseAnglesArePredictedAtRunTimeGivesTheSameBytes) {
  const std::vector<std::string> adaptive{"--end", "0.3 s", "--set", "time.step=adaptive", "--set", "time.tolerance=1e-3"};
  auto args = adaptive;
  args.insert(args.end(), {"--set", "record=true"});
  auto original = run(launch_args(scene_path("press_line.yaml"), "press_original", args), log("press_original"), 180);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const fs::path original_dir = run_folder("press_original");
  args = adaptive;
  args.insert(args.end(), {"--replay", "cam=" + (original_dir / "recording.mcap").string()});
  auto replayed = run(launch_args(scene_path("press_line.yaml"), "press_replayed", args), log("press_replayed"), 180);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  const auto steps = summary("press_original")["steps"].get<std::uint64_t>();
  EXPECT_EQ(summary("press_replayed")["steps"].get<std::uint64_t>(), steps);
  expect_live_nodes_repeat(original_dir, run_folder("press_replayed"), {"cvt", "follower"}, steps);
}

TEST_F(ReplayTest, ARecordingThatDoesNotFitTheSceneIsRefusedBeforeAnyProcessStarts) {
  auto original = run(launch_args(scene_path("nc_slide_loop.yaml"), "short", {"--end", "5 ms", "--set", "record=true"}),
                      log("short"), 180);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const std::string recording = (run_folder("short") / "recording.mcap").string();
  // 10 ms of scene, 5 ms of recording.
  auto r = run(launch_args(scene_path("nc_slide_loop.yaml"), "long", {"--end", "10 ms", "--replay", "servo=" + recording}),
               log("long"), 60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no sample for step 201"), std::string::npos) << r.output;
  auto unknown = run(launch_args(scene_path("nc_slide_loop.yaml"), "unknown", {"--replay", "amp=" + recording}), log("unknown"), 60);
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("no participant 'amp'"), std::string::npos) << unknown.output;
}

TEST_F(ReplayTest, APlayedRecordingRecordsAgainToTheSameBytes) {
  auto original = run(launch_args(scene_path("cam_press.yaml"), "cam", {"--end", "0.2 s", "--set", "record=true"}), log("cam"), 180);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const std::string recording = (run_folder("cam") / "recording.mcap").string();
  const auto recorded = data_samples(recording);
  ASSERT_EQ(recorded.size(), 2u);

  // Played unpaced onto a domain of our own and recorded there again (both in-process).
  transport::DomainLock domain = transport::DomainLock::acquire();
  ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
  auto again_file = (dir_ / "again.mcap").string();
  recorder::RecordOptions ro;
  ro.file = again_file;
  for (const auto& [topic, steps] : recorded) ro.topic_types[topic] = "";
  {
    record::McapReader reader(recording);
    for (const auto& [id, ch] : reader.channels())
      if (ro.topic_types.count(ch.topic)) ro.topic_types[ch.topic] = reader.schemas().at(ch.schema_id).name;
  }
  auto rec = recorder::start_recording(domain.domain_id(), ro);
  recorder::PlayOptions po;
  po.file = recording;
  po.rate = 0;
  const recorder::PlayReport report = recorder::play(domain.domain_id(), po);
  rec->stop();
  EXPECT_EQ(report.loops, 1);
  EXPECT_EQ(report.total, 2u * 201u);
  EXPECT_TRUE(data_samples(again_file) == recorded) << "the played samples differ from the recorded ones";

  // A time window: steps 50..100 of the 1 ms cam press, per topic.
  auto window_file = (dir_ / "window.mcap").string();
  ro.file = window_file;
  rec = recorder::start_recording(domain.domain_id(), ro);
  po.start_s = 0.05;
  po.end_s = 0.1;
  const recorder::PlayReport window = recorder::play(domain.domain_id(), po);
  rec->stop();
  for (const auto& [topic, steps] : data_samples(window_file)) {
    SCOPED_TRACE(topic);
    ASSERT_EQ(steps.size(), 51u);
    EXPECT_EQ(steps.begin()->first, 50u);
    EXPECT_EQ(steps.rbegin()->first, 100u);
  }
  EXPECT_EQ(window.total, 2u * 51u);
}

}  // namespace
}  // namespace mechsim::testing
