// `mechsim record`, `bag` and `topic` against real runs of the cam press over loopback DDS.
// Each test holds a DDS domain of its own (the launcher's flock scheme) and passes it to
// the launcher with --set dds.domain, so the recorder can be started first on it.
//
// What must hold: a recording has every step of every data topic (2001 samples for the
// 2003-step cam press: nothing dropped), its CSV export equals the nodes' own output logs
// bit for bit, a third-party MCAP reader (@mcap/core) opens it, and a recorder killed with
// SIGKILL mid-run leaves a file that is reported truncated and reads fully after
// `mechsim record --recover`.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "mechsim/transport/domain_lock.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/record/mcap_reader.h"
#include "npm_reader.h"
#include "recorder.h"
#include "run_command.h"

namespace mechsim::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kMechsim = std::string(MECHSIM_BIN_DIR) + "/mechsim";
const std::string kCamPress = std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cam_press.yaml";
// Steps 0..2003: 2 s at 1 ms, and three steps landed on the follower's load boundaries at
// 100, 120 and 210 deg, off the 1 ms grid (docs/accuracy.md "Discontinuities").
constexpr std::uint64_t kCamPressSamples = 2004;

// What @mcap/core saw in `file` (read_mcap.mjs prints JSON on stdout).
json read_with_mcap_core(const std::string& file) {
  const std::string out = file + ".mcap-core.json", err = file + ".mcap-core.err";
  const std::string cmd = "cd '" + std::string(MCAP_READER_WORK_DIR) + "' && node read_mcap.mjs '" + file + "' > '" + out +
                          "' 2> '" + err + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(err);
  json j = json::parse(slurp(out), nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << slurp(out) << slurp(err);
  return j.is_discarded() ? json::object() : j;
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

const json* find_topic(const json& info, const std::string& topic) {
  for (const auto& t : info["topics"])
    if (t["topic"] == topic) return &t;
  return nullptr;
}

class Record : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("mechsim-record-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    EXPECT_TRUE(processes_mentioning(dir_.string()).empty()) << "processes left behind";
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string domain() const { return std::to_string(domain_.domain_id()); }

  // Starts `mechsim record` on this test's domain and waits until it is recording.
  pid_t start_recorder(const std::string& tag, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv{kMechsim, "record", "--domain", domain(), "-o", path(tag + ".mcap"), "--json",
                                  path(tag + ".record.json")};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const pid_t pid = spawn(argv, path(tag + ".record.log"));
    for (int i = 0; i < 1000 && slurp(path(tag + ".record.log")).find("recording domain") == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_NE(slurp(path(tag + ".record.log")).find("recording domain"), std::string::npos) << slurp(path(tag + ".record.log"));
    return pid;
  }
  CommandResult stop_recorder(pid_t pid, const std::string& tag) {
    ::kill(pid, SIGINT);
    return wait_for(pid, path(tag + ".record.log"), 60);
  }
  std::vector<std::string> launch_args(const std::string& tag, std::vector<std::string> extra = {}) const {
    std::vector<std::string> a{kMechsim, "launch", kCamPress, "--runs-dir", path("runs-" + tag), "--json",
                               path(tag + ".summary.json"), "--no-plot", "--no-progress", "--set",
                               "dds.domain=" + domain()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  fs::path run_folder(const std::string& tag) const {
    for (const auto& e : fs::directory_iterator(path("runs-" + tag))) return e.path();
    return {};
  }
  json bag_info(const std::string& file) {
    const std::string out = file + ".info.json";
    CommandResult r = run({kMechsim, "bag", "info", file, "--json", out}, file + ".info.log", 60);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return json::parse(slurp(out), nullptr, false);
  }
  void require_npm_reader() {
    if (!testing::npm_reader::in_path("node")) GTEST_SKIP() << "node not installed (Debian packages nodejs, npm)";
    const std::string problem = testing::npm_reader::problem();  // installed by tools/install-test-deps.sh
    ASSERT_TRUE(problem.empty()) << problem;
  }

  fs::path dir_;
  transport::DomainLock domain_ = transport::DomainLock::acquire();
};

TEST_F(Record, RecordsEveryStepOfARunAndExportsExactlyTheNodesOutputs) {
  // "all": every topic, the data topics subscribed before the nodes exist (name:type), as
  // docs/recording.md advises for a run recorded from its first step.
  const pid_t all = start_recorder(
      "all", {"--topics", "cam/state:CamState,follower/state:FollowerState,mechsim/control,mechsim/status"});
  // "states": found through discovery by a regex, lz4.
  const pid_t states = start_recorder("states", {"--regex", ".*/state", "--compression", "lz4"});
  CommandResult run_result = run(launch_args("a"), path("a.launch.log"), 120);
  ASSERT_EQ(run_result.exit_code, 0) << run_result.output;
  CommandResult all_result = stop_recorder(all, "all");
  CommandResult states_result = stop_recorder(states, "states");
  ASSERT_EQ(all_result.exit_code, 0) << all_result.output;
  ASSERT_EQ(states_result.exit_code, 0) << states_result.output;

  // Nothing dropped: every step of both data topics, once.
  const json info = bag_info(path("all.mcap"));
  EXPECT_TRUE(info["complete"].get<bool>());
  EXPECT_FALSE(info["truncated"].get<bool>());
  EXPECT_EQ(info["compression"], json::array({"zstd"}));
  EXPECT_TRUE(info["problems"].empty()) << info["problems"].dump();
  for (const char* topic : {"cam/state", "follower/state"}) {
    SCOPED_TRACE(topic);
    const json* t = find_topic(info, topic);
    ASSERT_NE(t, nullptr) << info.dump(2);
    EXPECT_EQ((*t)["messages"].get<std::uint64_t>(), kCamPressSamples);
    EXPECT_EQ((*t)["steps"]["first"], 0);
    EXPECT_EQ((*t)["steps"]["last"], kCamPressSamples - 1);
    EXPECT_EQ((*t)["steps"]["missing"], 0);
    EXPECT_EQ((*t)["steps"]["duplicates"], 0);
    // publish time = simulated time of the sample: 0 .. 2 s.
    EXPECT_EQ((*t)["publish_time_s"][0].get<double>(), 0.0);
    EXPECT_EQ((*t)["publish_time_s"][1].get<double>(), 2.0);
    EXPECT_EQ((*t)["undecodable"], 0);
  }
  ASSERT_NE(find_topic(info, "mechsim/control"), nullptr);
  EXPECT_GE((*find_topic(info, "mechsim/control"))["messages"].get<int>(), 1);  // start
  ASSERT_NE(find_topic(info, "mechsim/status"), nullptr);
  EXPECT_GT((*find_topic(info, "mechsim/status"))["messages"].get<int>(), 0);
  EXPECT_EQ((*find_topic(info, "cam/state"))["type"], "mechsim::msg::CamState");

  // The recorder's own counts (printed and JSON) agree with the file.
  const json report = json::parse(slurp(path("all.record.json")));
  for (const auto& t : report["topics"])
    EXPECT_EQ(t["samples"], (*find_topic(info, t["topic"].get<std::string>()))["messages"]) << t.dump();
  EXPECT_NE(all_result.output.find("cam/state"), std::string::npos) << all_result.output;

  // The regex recorder took the two state topics only, lz4-compressed. It subscribes when
  // it discovers a writer, which races with the run's start (docs/recording.md): its
  // recording may begin late, but once begun nothing is missing up to the last step.
  const json states_info = bag_info(path("states.mcap"));
  ASSERT_EQ(states_info["topics"].size(), 2u) << states_info.dump(2);
  EXPECT_EQ(states_info["compression"], json::array({"lz4"}));
  for (const auto& t : states_info["topics"]) {
    EXPECT_TRUE(t["topic"] == "cam/state" || t["topic"] == "follower/state") << t.dump();
    if (t["messages"].get<std::uint64_t>() == 0) continue;  // subscribed as the run ended
    EXPECT_EQ(t["steps"]["last"], kCamPressSamples - 1) << t.dump();
    EXPECT_EQ(t["steps"]["missing"], 0) << t.dump();
  }

  // Export: the CSV values are the nodes' own outputs (same doubles, bit for bit), but for the
  // rows of the load boundaries (docs/accuracy.md "Discontinuities"): there the recording
  // holds what the cam published before the follower's sample of that instant reached it
  // (Jacobi), and the cam's log the row evaluated after it, whose shaft torque is the
  // follower's recorded drive torque of the same step.
  CommandResult exp = run({kMechsim, "bag", "export", path("all.mcap"), "--csv", path("csv")}, path("export.log"), 60);
  ASSERT_EQ(exp.exit_code, 0) << exp.output;
  const json summary = json::parse(slurp(path("a.summary.json")));
  const std::uint64_t run_id = std::stoull(summary["run_id"].get<std::string>(), nullptr, 16);
  std::set<double> event_times;
  for (const auto& e : summary["scheduled_events"]) event_times.insert(e["t_s"].get<double>());
  ASSERT_EQ(event_times.size(), 5u);
  {
    const cosim::OutputLog cam_log = cosim::read_output_log((run_folder("a") / "cam.outputs.bin").string());
    const auto follower_rows = read_csv(path("csv/follower_state.csv"));
    const int drive = [&] {
      for (std::size_t c = 0; c < follower_rows[0].size(); ++c)
        if (follower_rows[0][c] == "drive_torque") return static_cast<int>(c);
      return -1;
    }();
    ASSERT_GE(drive, 0);
    int checked = 0;
    for (std::size_t r = 0; r < cam_log.rows(); ++r)
      if (event_times.count(cam_log.data[0][r])) {
        ++checked;
        EXPECT_EQ(cam_log.data[static_cast<std::size_t>(cam_log.column("shaft_torque"))][r],
                  std::strtod(follower_rows[r + 1][static_cast<std::size_t>(drive)].c_str(), nullptr))
            << "row " << r;
      }
    EXPECT_EQ(checked, 5);
  }
  for (const auto& [node, csv] : {std::pair{"cam", "cam_state.csv"}, std::pair{"follower", "follower_state.csv"}}) {
    SCOPED_TRACE(node);
    const cosim::OutputLog log = cosim::read_output_log((run_folder("a") / (std::string(node) + ".outputs.bin")).string());
    const auto rows = read_csv(path("csv/" + std::string(csv)));
    ASSERT_EQ(rows.size(), kCamPressSamples + 1);  // + the header line
    ASSERT_EQ(log.rows(), kCamPressSamples);
    const auto& header = rows[0];
    ASSERT_GE(header.size(), 4u);
    EXPECT_EQ(header[0], "t");
    EXPECT_EQ(header[1], "step");
    EXPECT_EQ(header[2], "run_id");
    int compared = 0;
    for (std::size_t c = 3; c < header.size(); ++c) {
      const int col = log.column(header[c]);
      if (col < 0) continue;  // a topic field the block does not output (none for these types)
      ++compared;
      for (std::size_t r = 0; r < log.rows(); ++r)
        if (!event_times.count(log.data[0][r]) || std::string(node) == "follower") {  // Gauss-Seidel fed: equal
          ASSERT_EQ(std::strtod(rows[r + 1][c].c_str(), nullptr), log.data[col][r]) << header[c] << " row " << r;
        }
    }
    EXPECT_EQ(compared, static_cast<int>(header.size()) - 3) << "every topic field is a block output";
    for (std::size_t r = 0; r < log.rows(); ++r) {
      ASSERT_EQ(std::strtod(rows[r + 1][0].c_str(), nullptr), log.data[0][r]) << "t, row " << r;
      ASSERT_EQ(std::stoull(rows[r + 1][1]), r);
      ASSERT_EQ(std::stoull(rows[r + 1][2]), run_id);
    }
  }

  // A third-party reader opens the recording and sees the same.
  require_npm_reader();
  const json seen = read_with_mcap_core(path("all.mcap"));
  EXPECT_TRUE(seen["complete"].get<bool>()) << seen.dump(2);
  EXPECT_EQ(seen["indexed"]["message_counts"]["cam/state"], kCamPressSamples);
  EXPECT_EQ(seen["indexed"]["message_counts"]["follower/state"], kCamPressSamples);
  bool cam_schema = false;
  for (const auto& s : seen["indexed"]["schemas"])
    if (s["name"] == "mechsim::msg::CamState") {
      cam_schema = s["encoding"] == "omgidl" && s["data"].get<std::string>().find("struct CamState") != std::string::npos;
    }
  EXPECT_TRUE(cam_schema) << seen["indexed"]["schemas"].dump(2);
}

// The library the launcher embeds for a scene's `record:` section: readers created before
// the nodes exist (topic_types), wait_matched() before start, stop() -> counts. Every node's
// writer must have matched the recorder before the start (a match is seen by each side on
// its own, docs/recording.md): every step of the run is in the file.
TEST_F(Record, EmbeddedRecorderMatchesBeforeTheRunAndCountsEveryStep) {
  {
    // Nobody writes yet: not matched, and the timeout is honoured.
    ::setenv("CYCLONEDDS_URI", "file://" MECHSIM_SOURCE_DIR "/config/dds/cyclonedds-loopback.xml", 1);
    recorder::RecordOptions options;
    options.file = path("alone.mcap");
    options.topics.names = {"cam/state"};
    options.topic_types = {{"cam/state", "CamState"}};
    auto rec = recorder::start_recording(domain_.domain_id(), options);
    EXPECT_FALSE(rec->wait_matched({"cam/state"}, std::chrono::milliseconds(200)));
    EXPECT_TRUE(rec->stop().error.empty());
  }
  CommandResult launched = run(launch_args("e", {"--set", "record.regex=cam/state|follower/state|mechsim/status", "--set",
                                                 "record.compression=lz4", "--set", "record.file=" + path("embedded.mcap")}),
                               path("e.launch.log"), 120);
  ASSERT_EQ(launched.exit_code, 0) << launched.output;
  const json summary = json::parse(slurp(path("e.summary.json")));
  const json& recording = summary["recording"];
  EXPECT_TRUE(recording["complete"].get<bool>()) << recording.dump(1);
  ASSERT_EQ(recording["topics"].size(), 3u) << recording.dump(1);
  for (const auto& t : recording["topics"]) {
    if (t["topic"] == "mechsim/status") {
      EXPECT_FALSE(t["reliable"].get<bool>());
      EXPECT_GT(t["recorded"].get<std::uint64_t>(), 0u);  // best effort: counted, not required complete
    } else {
      EXPECT_TRUE(t["reliable"].get<bool>());
      EXPECT_EQ(t["recorded"].get<std::uint64_t>(), kCamPressSamples) << t.dump();
      EXPECT_EQ(t["published"].get<std::uint64_t>(), kCamPressSamples) << t.dump();
    }
  }
  const json info = bag_info(path("embedded.mcap"));
  EXPECT_TRUE(info["complete"].get<bool>());
  EXPECT_EQ(info["compression"], json::array({"lz4"}));
  EXPECT_EQ(info["messages"], recording["messages"]);
}

TEST_F(Record, KilledRecorderLeavesATruncatedFileThatRecoverRebuilds) {
  require_npm_reader();
  const pid_t rec = start_recorder("killed");
  // 20 s simulated: long enough to kill the recorder while the nodes run.
  const pid_t launcher = spawn(launch_args("k", {"--end", "20 s"}), path("k.launch.log"));
  // Kill once at least two chunks are on disk (a chunk closes every second or 1 MiB).
  bool chunks_written = false;
  for (int i = 0; i < 600 && !chunks_written; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    try {
      chunks_written = record::McapReader(path("killed.mcap")).chunks().size() >= 2;
    } catch (const std::exception&) {
      // not even the header yet
    }
  }
  ASSERT_TRUE(chunks_written) << slurp(path("k.launch.log"));
  ::kill(rec, SIGKILL);
  CommandResult killed = wait_for(rec, path("killed.record.log"), 10);
  EXPECT_EQ(killed.exit_code, -1);  // died by the signal
  // The run's outcome is not judged here: the nodes' writers wait for the vanished reliable
  // reader until its lease expires (10 s by default), which the launcher may declare a
  // hung node first (docs/recording.md). Only the recording is.
  CommandResult launched = wait_for(launcher, path("k.launch.log"), 180);
  EXPECT_FALSE(launched.timed_out) << launched.output;

  const json cut = bag_info(path("killed.mcap"));
  EXPECT_TRUE(cut["truncated"].get<bool>()) << cut.dump(2);
  EXPECT_FALSE(cut["complete"].get<bool>());
  const json* cam = find_topic(cut, "cam/state");
  ASSERT_NE(cam, nullptr) << cut.dump(2);
  EXPECT_GT((*cam)["messages"].get<int>(), 0);
  EXPECT_EQ((*cam)["steps"]["missing"], 0);  // no gap up to the kill

  const json seen_cut = read_with_mcap_core(path("killed.mcap"));
  EXPECT_FALSE(seen_cut["complete"].get<bool>()) << seen_cut.dump(2);
  EXPECT_FALSE(seen_cut["stream"]["done"].get<bool>());
  EXPECT_TRUE(seen_cut["stream"]["error"].is_null()) << seen_cut["stream"].dump(2);
  for (const auto& t : cut["topics"])
    EXPECT_EQ(seen_cut["stream"]["message_counts"].value(t["topic"].get<std::string>(), 0), t["messages"].get<int>())
        << t["topic"];

  CommandResult rec_fix = run({kMechsim, "record", "--recover", path("killed.mcap"), "-o", path("recovered.mcap")},
                              path("recover.log"), 60);
  ASSERT_EQ(rec_fix.exit_code, 0) << rec_fix.output;
  const json fixed = bag_info(path("recovered.mcap"));
  EXPECT_TRUE(fixed["complete"].get<bool>());
  EXPECT_TRUE(fixed["problems"].empty()) << fixed["problems"].dump();
  EXPECT_EQ(fixed["messages"], cut["messages"]);
  const json seen_fixed = read_with_mcap_core(path("recovered.mcap"));
  EXPECT_TRUE(seen_fixed["complete"].get<bool>()) << seen_fixed.dump(2);
  EXPECT_TRUE(seen_fixed["indexed"]["ok"].get<bool>());
  for (const auto& t : cut["topics"])
    EXPECT_EQ(seen_fixed["indexed"]["message_counts"].value(t["topic"].get<std::string>(), 0), t["messages"].get<int>())
        << t["topic"];
}

TEST_F(Record, TopicCommandsShowARunningScene) {
  // A long run, interrupted once the commands have seen it. A process per node: `topic
  // list` counts DDS readers, and a member of a process group reads its partner's topic
  // from memory, not through DDS (docs/recording.md).
  const pid_t launcher = spawn(launch_args("t", {"--end", "600 s", "--set", "processes=per_participant"}), path("t.launch.log"));
  std::string list;
  for (int i = 0; i < 30 && list.find("follower/state") == std::string::npos; ++i)
    list = run({kMechsim, "topic", "list", "--domain", domain(), "--wait", "0.5"}, path("list.log"), 30).output;
  // Each state topic: its node writes it, the partner reads it.
  EXPECT_NE(list.find("cam/state        mechsim::msg::CamState"), std::string::npos) << list;
  std::istringstream lines(list);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream cells(line);
    std::string topic, type;
    int pub = -1, sub = -1;
    cells >> topic >> type >> pub >> sub;
    if (topic == "cam/state" || topic == "follower/state") {
      ++rows;
      EXPECT_EQ(pub, 1) << line;
      EXPECT_EQ(sub, 1) << line;
    }
    if (topic == "mechsim/control") {
      EXPECT_EQ(pub, 1) << line;  // the launcher
    }
    if (topic == "mechsim/status") {
      EXPECT_EQ(pub, 2) << line;  // both nodes
    }
  }
  EXPECT_EQ(rows, 2) << list;

  CommandResult echo = run({kMechsim, "topic", "echo", "cam/state", "--domain", domain(), "--count", "3", "--timeout", "20"},
                           path("echo.log"), 60);
  EXPECT_EQ(echo.exit_code, 0) << echo.output;
  std::size_t docs = 0;
  for (std::size_t at = 0; (at = echo.output.find("--- # cam/state (mechsim::msg::CamState)", at)) != std::string::npos; ++at)
    ++docs;
  EXPECT_EQ(docs, 3u) << echo.output;
  for (const char* field : {"\nrun_id: 0x", "\nstep: ", "\nt: ", "\nangle: ", "\nspeed: ", "\ndrive_power: "})
    EXPECT_NE(echo.output.find(field), std::string::npos) << field << "\n" << echo.output;

  CommandResult hz = run({kMechsim, "topic", "hz", "follower/state", "--domain", domain(), "--window", "0.5", "--count",
                          "2", "--timeout", "20"},
                         path("hz.log"), 60);
  EXPECT_EQ(hz.exit_code, 0) << hz.output;
  std::size_t windows = 0;
  for (std::size_t at = 0; (at = hz.output.find(" Hz (", at)) != std::string::npos; ++at) ++windows;
  EXPECT_EQ(windows, 2u) << hz.output;

  ::kill(launcher, SIGINT);
  CommandResult stopped = wait_for(launcher, path("t.launch.log"), 60);
  EXPECT_EQ(stopped.exit_code, 130) << stopped.output;
}

}  // namespace
}  // namespace mechsim::testing
