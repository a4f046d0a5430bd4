// `mechsim bag info` / `bag export` on damaged recordings (issue 28): a damaged chunk is
// listed as a problem with its offset and skipped, the sound chunks are still counted and
// exported, the file is "complete" only when nothing is wrong, and --strict refuses. The
// recordings are written by McapWriter (record_test_support.h) and then altered.
#include <gtest/gtest.h>

#include <numeric>
#include <string>

#include "bag_inspect.h"
#include "record_test_support.h"

namespace mechsim::recorder {
namespace {

using record::test::le_u32;

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
  for (const auto& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

class BagDamage : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.file("clean.mcap");
    record::WriterOptions options;
    options.chunk_size = 4096;  // several chunks
    sample_ = record::test::write_sample(path_, options, 600);
    bytes_ = record::test::read_bytes(path_);
    const record::McapReader reader(path_);
    chunks_ = reader.chunks();
    ASSERT_GE(chunks_.size(), 3u);
    in_chunk1_ = reader.read_chunk(chunks_[1]).size();
  }
  std::string with(const std::string& name, uint64_t at, uint64_t value, int n) {
    auto b = bytes_;
    for (int i = 0; i < n; ++i) b.at(at + i) = uint8_t(value >> (8 * i));
    const std::string p = dir_.file(name);
    record::test::write_bytes(p, b.data(), b.size());
    return p;
  }
  // Chunk 1 with its stored CRC off by one bit.
  std::string bad_crc() {
    const uint64_t at = chunks_[1].chunk_start_offset + 9 + 24;
    return with("bad_crc.mcap", at, le_u32(bytes_, at) ^ 1u, 4);
  }

  record::test::ScratchDir dir_;
  std::string path_;
  record::test::SampleRecording sample_;
  std::vector<uint8_t> bytes_;
  std::vector<record::ChunkInfo> chunks_;
  std::size_t in_chunk1_ = 0;
};

TEST_F(BagDamage, SoundFileIsComplete) {
  const BagInfo info = inspect_bag(path_);
  EXPECT_TRUE(info.complete);
  EXPECT_FALSE(info.damaged);
  EXPECT_TRUE(info.problems.empty());
  EXPECT_EQ(info.messages, sample_.messages.size());
  EXPECT_EQ(exit_code(info), 0);
}

TEST_F(BagDamage, DamagedChunkIsListedAndTheOthersCounted) {
  const std::string path = bad_crc();
  const BagInfo info = inspect_bag(path);
  EXPECT_FALSE(info.complete);
  EXPECT_TRUE(info.damaged);
  EXPECT_EQ(info.chunks_skipped, 1u);
  EXPECT_EQ(info.messages, sample_.messages.size() - in_chunk1_);
  EXPECT_TRUE(any_contains(info.problems, "Chunk at offset " + std::to_string(chunks_[1].chunk_start_offset) +
                                              ": CRC mismatch"));
  const std::string text = format_bag_info(info);
  EXPECT_NE(text.find("state:        DAMAGED"), std::string::npos) << text;
  EXPECT_NE(text.find("1 damaged chunks skipped"), std::string::npos) << text;
  EXPECT_EQ(to_json(info)["complete"], false);
  EXPECT_EQ(exit_code(info), 3);

  BagReadOptions strict;
  strict.strict = true;
  try {
    (void)inspect_bag(path, strict);
    FAIL() << "--strict read a damaged file";
  } catch (const record::McapError& e) {
    EXPECT_NE(std::string(e.what()).find("offset " + std::to_string(chunks_[1].chunk_start_offset)), std::string::npos)
        << e.what();
  }
}

// The lie that passed as complete: chunk 0's record length set to 2^63.
TEST_F(BagDamage, RecordLengthOf2To63IsNotComplete) {
  const uint64_t at = chunks_[0].chunk_start_offset;
  const BagInfo info = inspect_bag(with("len.mcap", at + 1, uint64_t(1) << 63, 8));
  EXPECT_FALSE(info.complete);
  EXPECT_EQ(exit_code(info), 3);  // the old reader said complete, exit 0
  EXPECT_TRUE(any_contains(info.problems, "Chunk record at offset " + std::to_string(at) + " claims 9223372036854775808"))
      << to_json(info)["problems"].dump(1);
}

TEST_F(BagDamage, ExportSkipsTheDamagedChunkOnly) {
  const std::string path = bad_crc();
  const BagExport result = export_csv(path, dir_.file("csv"));
  ASSERT_EQ(result.skipped_chunks.size(), 1u);
  EXPECT_EQ(exit_code(result), 3);
  EXPECT_NE(result.skipped_chunks[0].find("offset " + std::to_string(chunks_[1].chunk_start_offset)), std::string::npos)
      << result.skipped_chunks[0];
  // Every message of the sound chunks is either a row or counted as undecodable.
  const std::uint64_t seen = std::accumulate(result.topics.begin(), result.topics.end(), std::uint64_t{0},
                                             [](std::uint64_t s, const ExportedTopic& t) { return s + t.rows + t.skipped; });
  EXPECT_EQ(seen, sample_.messages.size() - in_chunk1_);

  BagReadOptions strict;
  strict.strict = true;
  EXPECT_THROW(export_csv(path, dir_.file("csv_strict"), strict), record::McapError);
  EXPECT_EQ(exit_code(export_csv(path_, dir_.file("csv_clean"), strict)), 0);
}

}  // namespace
}  // namespace mechsim::recorder
