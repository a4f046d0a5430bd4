// mechsim's recordings must be readable by MCAP readers nobody here wrote (DESIGN.md,
// Recording). This runs the @mcap/core npm reader (read_mcap.mjs) on files from McapWriter:
// complete files through its indexed and streaming readers, a truncated file that it must
// call incomplete, and the same file after recover().
//
// node_modules: tools/install-test-deps.sh (run by tools/run-tests.sh) installs the reader
// into the build tree (MCAP_READER_WORK_DIR), pinned by package-lock.json; this test never
// runs npm (npm_reader.h). Without node the test is skipped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_writer.h"
#include "npm_reader.h"
#include "record_test_support.h"

namespace mechsim::record {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct RunResult {
  int exit_code = -1;  // -1: killed by a signal (or the timeout)
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs argv (looked up in PATH) in `cwd` with stdout and stderr captured in files under
// `io_dir` (private to the calling test: tests run in parallel), killed after `timeout`:
// npm without network could otherwise hang the test run.
RunResult run(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& io_dir,
              std::chrono::seconds timeout) {
  const fs::path out = io_dir / "run.out", err = io_dir / "run.err";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fo < 0 || fe < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(126);
    ::dup2(fo, 1);
    ::dup2(fe, 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    ::_exit(127);
  }
  RunResult r;
  if (pid < 0) return r;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      r.err = "timed out after " + std::to_string(timeout.count()) + " s\n";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = slurp(out);
  r.err += slurp(err);
  return r;
}

// What read_mcap.mjs printed for `file` (its output captured next to `file`).
json read_with_mcap_core(const std::string& file) {
  const RunResult r = run({"node", "read_mcap.mjs", file}, MCAP_READER_WORK_DIR,
                          fs::path(file).parent_path(), std::chrono::seconds(120));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  try {
    return json::parse(r.out);
  } catch (const json::exception& e) {
    ADD_FAILURE() << "read_mcap.mjs printed no JSON: " << e.what() << "\n" << r.out << r.err;
    return json::object();
  }
}

// Message counts per topic as our own reader sees them, in read_mcap.mjs's shape.
json counts_by_topic(const McapReader& reader) {
  json counts = json::object();
  for (const auto& [id, n] : reader.statistics().channel_message_counts)
    counts[reader.channels().at(id).topic] = n;
  return counts;
}

class McapNpmReader : public ::testing::TestWithParam<Compression> {
 protected:
  void SetUp() override {
    if (!testing::npm_reader::in_path("node"))
      GTEST_SKIP() << "node not installed: the third-party MCAP reader check needs it (Debian packages nodejs and npm)";
    const std::string problem = testing::npm_reader::problem();
    ASSERT_TRUE(problem.empty()) << problem;
  }
  test::ScratchDir dir_;
};

TEST_P(McapNpmReader, CompleteRecordingReadsIdentically) {
  const std::string path = dir_.file("complete.mcap");
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_size = 8 * 1024;  // ~30 chunks: exercises the chunk index
  const auto written = test::write_sample(path, options, 3000);
  const McapReader ours(path);

  const json seen = read_with_mcap_core(path);
  ASSERT_TRUE(seen.contains("indexed")) << seen.dump(2);
  const json& indexed = seen["indexed"];
  ASSERT_TRUE(indexed["ok"].get<bool>()) << indexed.dump(2);
  EXPECT_TRUE(seen["complete"].get<bool>());
  EXPECT_EQ(indexed["header"]["library"], "mechsim");

  ASSERT_EQ(indexed["schemas"].size(), written.schemas.size());
  for (std::size_t k = 0; k < written.schemas.size(); ++k) {
    EXPECT_EQ(indexed["schemas"][k]["id"], written.schemas[k].id);
    EXPECT_EQ(indexed["schemas"][k]["name"], written.schemas[k].name);
    EXPECT_EQ(indexed["schemas"][k]["encoding"], "omgidl");
    EXPECT_EQ(indexed["schemas"][k]["data"], written.schemas[k].data);
  }
  ASSERT_EQ(indexed["channels"].size(), written.channels.size());
  json expected_counts = json::object(), expected_bytes = json::object();
  for (std::size_t k = 0; k < written.channels.size(); ++k) {
    const Channel& c = written.channels[k];
    EXPECT_EQ(indexed["channels"][k]["topic"], c.topic);
    EXPECT_EQ(indexed["channels"][k]["schema_id"], c.schema_id);
    EXPECT_EQ(indexed["channels"][k]["message_encoding"], "cdr");
    EXPECT_EQ(indexed["channels"][k]["metadata"], json(c.metadata));
    expected_counts[c.topic] = 0;
    expected_bytes[c.topic] = 0;
  }
  for (const auto& m : written.messages) {
    const std::string& topic = written.channels[m.channel_id - 1].topic;
    expected_counts[topic] = expected_counts[topic].get<int>() + 1;
    expected_bytes[topic] = expected_bytes[topic].get<int>() + static_cast<int>(m.data.size());
  }
  EXPECT_EQ(indexed["message_counts"], expected_counts);
  EXPECT_EQ(indexed["message_bytes"], expected_bytes);
  EXPECT_TRUE(indexed["log_time_ordered"].get<bool>());
  EXPECT_EQ(indexed["statistics"]["message_count"], 3000);
  EXPECT_EQ(indexed["statistics"]["chunk_count"], ours.chunks().size());
  EXPECT_EQ(indexed["chunk_indexes"], ours.chunks().size());

  // The streaming pass walks every record (summary included) and checks chunk CRCs.
  const json& stream = seen["stream"];
  EXPECT_TRUE(stream["done"].get<bool>()) << stream.dump(2);
  EXPECT_TRUE(stream["error"].is_null()) << stream.dump(2);
  EXPECT_EQ(stream["message_counts"], expected_counts);
  EXPECT_EQ(stream["message_bytes"], expected_bytes);
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapNpmReader,
                         ::testing::Values(Compression::none, Compression::zstd, Compression::lz4),
                         [](const auto& info) {
                           const std::string n = compression_name(info.param);
                           return n.empty() ? std::string("none") : n;
                         });

class McapNpmReaderTruncated : public McapNpmReader {};

TEST_P(McapNpmReaderTruncated, IsReportedTruncatedAndReadsFullyAfterRecover) {
  const std::string path = dir_.file("complete.mcap");
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_size = 8 * 1024;
  test::write_sample(path, options, 3000);
  // Cut in the middle of the 10th chunk, as a killed recorder would leave it.
  const ChunkInfo cut_chunk = McapReader(path).chunks().at(9);
  const auto bytes = test::read_bytes(path);
  const std::string cut = dir_.file("cut.mcap");
  test::write_bytes(cut, bytes.data(), cut_chunk.chunk_start_offset + cut_chunk.chunk_length / 2);
  const McapReader ours_cut(cut);
  ASSERT_TRUE(ours_cut.truncated());
  ASSERT_EQ(ours_cut.chunks().size(), 9u);

  const json seen_cut = read_with_mcap_core(cut);
  ASSERT_TRUE(seen_cut.contains("stream")) << seen_cut.dump(2);
  EXPECT_FALSE(seen_cut["complete"].get<bool>());
  EXPECT_FALSE(seen_cut["indexed"]["ok"].get<bool>());  // no footer to index from
  EXPECT_FALSE(seen_cut["stream"]["done"].get<bool>());
  EXPECT_TRUE(seen_cut["stream"]["error"].is_null()) << seen_cut["stream"].dump(2);
  // The streaming reader sees exactly the messages of the 9 complete chunks, as we do.
  EXPECT_EQ(seen_cut["stream"]["message_counts"], counts_by_topic(ours_cut));

  const std::string fixed = dir_.file("recovered.mcap");
  const RecoveryReport report = recover(cut, fixed);
  EXPECT_EQ(report.messages, ours_cut.statistics().message_count);
  const json seen_fixed = read_with_mcap_core(fixed);
  ASSERT_TRUE(seen_fixed.contains("indexed")) << seen_fixed.dump(2);
  EXPECT_TRUE(seen_fixed["complete"].get<bool>()) << seen_fixed.dump(2);
  EXPECT_TRUE(seen_fixed["indexed"]["ok"].get<bool>()) << seen_fixed["indexed"].dump(2);
  EXPECT_EQ(seen_fixed["indexed"]["message_counts"], counts_by_topic(ours_cut));
  EXPECT_EQ(seen_fixed["indexed"]["statistics"]["message_count"], report.messages);
  EXPECT_EQ(seen_fixed["stream"]["message_counts"], counts_by_topic(ours_cut));
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapNpmReaderTruncated,
                         ::testing::Values(Compression::zstd, Compression::lz4),
                         [](const auto& info) { return compression_name(info.param); });

TEST(NpmReaderSetup, AMissingInstallIsReportedAtOnceWithTheCommandToRun) {
  // An empty folder stands for a build tree where tools/install-test-deps.sh could not
  // reach the registry: the check names the folder and the command, runs no npm and
  // creates nothing (no node_modules appears).
  test::ScratchDir dir;
  const fs::path empty = dir.file("no-reader");
  fs::create_directories(empty);
  const std::string why = testing::npm_reader::problem(MCAP_READER_SOURCE_DIR, empty);
  EXPECT_NE(why.find("not installed in " + empty.string()), std::string::npos) << why;
  EXPECT_NE(why.find("run tools/install-test-deps.sh"), std::string::npos) << why;
  EXPECT_EQ(why.find('\n'), std::string::npos) << "one line: " << why;
  EXPECT_TRUE(fs::is_empty(empty));
}

TEST(NpmReaderSetup, AReaderFromAnotherLockFileIsNotUsed) {
  // Installed, but from an older lock: the tests must not run an unpinned reader.
  test::ScratchDir dir;
  const fs::path work = dir.file("old-reader");
  fs::create_directories(work / "node_modules" / "@mcap" / "core");
  fs::copy_file(fs::path(MCAP_READER_SOURCE_DIR) / "read_mcap.mjs", work / "read_mcap.mjs");
  std::ofstream(work / ".installed-package-lock.json") << "{\"lockfileVersion\": 1}";
  const std::string why = testing::npm_reader::problem(MCAP_READER_SOURCE_DIR, work);
  EXPECT_NE(why.find("another package-lock.json"), std::string::npos) << why;
}

}  // namespace
}  // namespace mechsim::record
