// A recording cut at any byte (what a crash of the recorder leaves) must never crash the
// reader, and recovery must return exactly the messages of the chunks that were complete
// before the cut: nothing invented, nothing complete lost.
#include <gtest/gtest.h>

#include <set>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_writer.h"
#include "record_test_support.h"

namespace mechsim::record {
namespace {

class McapTruncation : public ::testing::TestWithParam<Compression> {};

TEST_P(McapTruncation, EveryCutKeepsExactlyTheCompleteChunks) {
  test::ScratchDir dir;
  const std::string path = dir.file("full.mcap");
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_size = 6 * 1024;
  test::write_sample(path, options, 2000);
  const std::vector<uint8_t> bytes = test::read_bytes(path);

  const McapReader full(path);
  ASSERT_TRUE(full.complete());
  struct ChunkMessages {
    uint64_t end;  // first byte after the chunk record
    std::vector<Message> messages;
  };
  std::vector<ChunkMessages> chunks;
  for (const ChunkInfo& c : full.chunks())
    chunks.push_back({c.chunk_start_offset + c.chunk_length, full.read_chunk(c)});
  ASSERT_GT(chunks.size(), 5u);

  // Cuts every 997 bytes (a prime, so cuts land at varied places inside records) plus the
  // boundary cases: one byte short of each chunk's end, exactly at it, and the file's end.
  std::set<uint64_t> cuts;
  for (uint64_t cut = 0; cut < bytes.size(); cut += 997) cuts.insert(cut);
  for (const auto& c : chunks) cuts.insert({c.end - 1, c.end});
  cuts.insert({bytes.size() - 1, bytes.size()});

  const std::string cut_path = dir.file("cut.mcap");
  const std::string recovered_path = dir.file("recovered.mcap");
  for (const uint64_t cut : cuts) {
    SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of " + std::to_string(bytes.size()));
    test::write_bytes(cut_path, bytes.data(), cut);
    if (cut < 8) {  // not even the magic: not an MCAP file
      EXPECT_THROW(McapReader{cut_path}, McapError);
      EXPECT_THROW(recover(cut_path, recovered_path), McapError);
      continue;
    }
    std::vector<Message> expected;
    for (const auto& c : chunks)
      if (c.end <= cut) expected.insert(expected.end(), c.messages.begin(), c.messages.end());

    const McapReader reader(cut_path);
    EXPECT_EQ(reader.truncated(), cut != bytes.size());
    EXPECT_LE(reader.scan_end(), cut);
    const std::vector<Message> read = reader.read_messages();
    EXPECT_EQ(read.size(), expected.size());
    EXPECT_TRUE(read == expected);
    EXPECT_EQ(reader.statistics().message_count, expected.size());
    // Every message read has its channel and schema (they precede the chunks).
    for (const auto& m : read) {
      ASSERT_TRUE(reader.channels().count(m.channel_id));
      EXPECT_TRUE(reader.schemas().count(reader.channels().at(m.channel_id).schema_id));
    }

    const RecoveryReport report = recover(cut_path, recovered_path);
    EXPECT_EQ(report.input_complete, cut == bytes.size());
    EXPECT_EQ(report.messages, expected.size());
    EXPECT_EQ(report.chunks_dropped, 0u);
    const McapReader recovered(recovered_path);
    EXPECT_TRUE(recovered.complete());
    EXPECT_EQ(recovered.statistics().message_count, expected.size());
    EXPECT_TRUE(recovered.read_messages() == expected);
    EXPECT_TRUE(recovered.verify().empty());
  }
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapTruncation,
                         ::testing::Values(Compression::none, Compression::zstd, Compression::lz4),
                         [](const auto& info) {
                           const std::string n = compression_name(info.param);
                           return n.empty() ? std::string("none") : n;
                         });

TEST(McapTruncation, ReaderReportsWhereAndWhyItStopped) {
  test::ScratchDir dir;
  const std::string path = dir.file("full.mcap");
  WriterOptions options;
  options.chunk_size = 4096;
  test::write_sample(path, options, 600);
  const McapReader full(path);
  ASSERT_GE(full.chunks().size(), 3u);
  const ChunkInfo& second = full.chunks()[1];
  // Cut in the middle of the second chunk: the scan keeps the first chunk and its message
  // indexes, and stops at the start of the second.
  const auto bytes = test::read_bytes(path);
  const std::string cut_path = dir.file("cut.mcap");
  test::write_bytes(cut_path, bytes.data(), second.chunk_start_offset + second.chunk_length / 2);
  const McapReader reader(cut_path);
  EXPECT_TRUE(reader.truncated());
  EXPECT_FALSE(reader.complete());
  EXPECT_EQ(reader.scan_end(), second.chunk_start_offset);
  EXPECT_NE(reader.stop_reason().find("Chunk"), std::string::npos) << reader.stop_reason();
  ASSERT_EQ(reader.chunks().size(), 1u);
  EXPECT_EQ(reader.chunks()[0], full.chunks()[0]);  // message index offsets found by the scan
}

TEST(McapTruncation, CutInsideTheSummaryKeepsAllData) {
  // A crash while the summary is being written loses no message: DataEnd is already there.
  test::ScratchDir dir;
  const std::string path = dir.file("full.mcap");
  test::write_sample(path, {}, 900);
  const auto bytes = test::read_bytes(path);
  const uint64_t summary_start = test::le_u64(bytes, bytes.size() - 8 - 29 + 9);
  const std::string cut_path = dir.file("cut.mcap");
  test::write_bytes(cut_path, bytes.data(), summary_start + 5);
  const McapReader reader(cut_path);
  EXPECT_TRUE(reader.truncated());
  EXPECT_EQ(reader.stop_reason(), "DataEnd");
  EXPECT_EQ(reader.statistics().message_count, 900u);
}

}  // namespace
}  // namespace mechsim::record
