// The bytes on disk follow the MCAP specification. These tests parse the file with their
// own few lines of little-endian decoding (not the library's reader), so a mistake shared
// by writer and reader cannot hide here.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "crc32.h"
#include "mechsim/record/mcap_writer.h"
#include "record_test_support.h"

namespace mechsim::record {
namespace {

using test::le_u16;
using test::le_u32;
using test::le_u64;

struct RawRecord {
  uint8_t opcode;
  uint64_t offset;
  uint64_t length;  // content only
};

// Records from `begin` to `end`, which must tile the range exactly.
std::vector<RawRecord> walk(const std::vector<uint8_t>& b, uint64_t begin, uint64_t end) {
  std::vector<RawRecord> out;
  uint64_t pos = begin;
  while (pos < end) {
    const RawRecord r{b.at(pos), pos, le_u64(b, pos + 1)};
    out.push_back(r);
    pos += 9 + r.length;
  }
  EXPECT_EQ(pos, end) << "records overrun their section";
  return out;
}

uint32_t crc_of(const std::vector<uint8_t>& b, uint64_t begin, uint64_t end) {
  return detail::crc32_update(0, std::span(b).subspan(begin, end - begin));
}

class McapLayout : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.file("layout.mcap");
    WriterOptions options;
    options.chunk_size = 8 * 1024;
    options.profile = "x-mechsim";
    sample_ = test::write_sample(path_, options, 1500);
    bytes_ = test::read_bytes(path_);
    ASSERT_GT(bytes_.size(), 8u + 37u);
    footer_ = bytes_.size() - 8 - 29;
    summary_start_ = le_u64(bytes_, footer_ + 9);
    summary_offset_start_ = le_u64(bytes_, footer_ + 17);
  }

  test::ScratchDir dir_;
  std::string path_;
  test::SampleRecording sample_;
  std::vector<uint8_t> bytes_;
  uint64_t footer_ = 0, summary_start_ = 0, summary_offset_start_ = 0;
};

TEST_F(McapLayout, StartsAndEndsWithMagicAroundHeaderAndFooter) {
  EXPECT_TRUE(std::equal(test::kMcapMagic.begin(), test::kMcapMagic.end(), bytes_.begin()));
  EXPECT_TRUE(std::equal(test::kMcapMagic.begin(), test::kMcapMagic.end(), bytes_.end() - 8));
  // Header right after the magic: profile and library strings.
  ASSERT_EQ(bytes_[8], 0x01);
  const uint32_t profile_len = le_u32(bytes_, 17);
  EXPECT_EQ(std::string(bytes_.begin() + 21, bytes_.begin() + 21 + profile_len), "x-mechsim");
  EXPECT_EQ(le_u64(bytes_, 9), 4 + profile_len + 4 + std::string("mechsim").size());
  // Footer: opcode 0x02, content length 20.
  EXPECT_EQ(bytes_[footer_], 0x02);
  EXPECT_EQ(le_u64(bytes_, footer_ + 1), 20u);
}

TEST_F(McapLayout, DataSectionEndsWithDataEndWhoseCrcCoversEverythingBefore) {
  const auto data = walk(bytes_, 8, summary_start_);
  ASSERT_FALSE(data.empty());
  EXPECT_EQ(data.front().opcode, 0x01);
  const RawRecord& end = data.back();
  ASSERT_EQ(end.opcode, 0x0F);
  EXPECT_EQ(end.length, 4u);
  EXPECT_EQ(le_u32(bytes_, end.offset + 9), crc_of(bytes_, 0, end.offset));
  // Only data-section record kinds appear before DataEnd.
  const std::set<uint8_t> allowed{0x01, 0x03, 0x04, 0x05, 0x06, 0x07, 0x09, 0x0C};
  for (std::size_t i = 0; i + 1 < data.size(); ++i) EXPECT_TRUE(allowed.count(data[i].opcode));
}

TEST_F(McapLayout, SchemasAndChannelsPrecedeEveryChunkOutsideChunks) {
  // Crash safety: a reader of a truncated file must meet Schema and Channel before any
  // chunk, because the summary that would repeat them is never written.
  const auto data = walk(bytes_, 8, summary_start_);
  std::size_t schemas = 0, channels = 0;
  for (const auto& r : data) {
    if (r.opcode == 0x03) ++schemas;
    if (r.opcode == 0x04) ++channels;
    if (r.opcode == 0x06) {
      EXPECT_EQ(schemas, 2u);
      EXPECT_EQ(channels, 3u);
    }
  }
}

TEST_F(McapLayout, SummaryOffsetsPointAtTheirGroups) {
  ASSERT_NE(summary_start_, 0u);
  ASSERT_GT(summary_offset_start_, summary_start_);
  const auto summary = walk(bytes_, summary_start_, summary_offset_start_);
  const auto offsets = walk(bytes_, summary_offset_start_, footer_);
  std::map<uint8_t, std::pair<uint64_t, uint64_t>> groups;
  for (const auto& r : offsets) {
    ASSERT_EQ(r.opcode, 0x0E);
    ASSERT_EQ(r.length, 17u);
    groups[bytes_[r.offset + 9]] = {le_u64(bytes_, r.offset + 10), le_u64(bytes_, r.offset + 18)};
  }
  // Schema, Channel, Statistics and ChunkIndex groups, in that order, tiling the summary.
  ASSERT_EQ(groups.size(), 4u);
  uint64_t expected_start = summary_start_;
  for (uint8_t opcode : {0x03, 0x04, 0x0B, 0x08}) {
    ASSERT_TRUE(groups.count(opcode)) << int(opcode);
    const auto [start, length] = groups[opcode];
    EXPECT_EQ(start, expected_start) << int(opcode);
    const auto in_group = walk(bytes_, start, start + length);
    for (const auto& r : in_group) EXPECT_EQ(r.opcode, opcode);
    expected_start = start + length;
  }
  EXPECT_EQ(expected_start, summary_offset_start_);
  std::size_t chunk_indexes = 0;
  for (const auto& r : summary) chunk_indexes += r.opcode == 0x08;
  EXPECT_EQ(walk(bytes_, groups[0x08].first, groups[0x08].first + groups[0x08].second).size(),
            chunk_indexes);
}

TEST_F(McapLayout, SummaryCrcCoversSummaryOffsetsAndFooterPrefix) {
  EXPECT_EQ(le_u32(bytes_, footer_ + 25), crc_of(bytes_, summary_start_, footer_ + 25));
}

TEST_F(McapLayout, StatisticsRecordCountsWhatWasWritten) {
  for (const auto& r : walk(bytes_, summary_start_, summary_offset_start_)) {
    if (r.opcode != 0x0B) continue;
    const uint64_t c = r.offset + 9;
    EXPECT_EQ(le_u64(bytes_, c), 1500u);       // message_count
    EXPECT_EQ(le_u16(bytes_, c + 8), 2u);      // schema_count
    EXPECT_EQ(le_u32(bytes_, c + 10), 3u);     // channel_count
    EXPECT_EQ(le_u32(bytes_, c + 14), 0u);     // attachment_count
    EXPECT_EQ(le_u32(bytes_, c + 18), 0u);     // metadata_count
    EXPECT_EQ(le_u64(bytes_, c + 26), sample_.messages.front().log_time);
    EXPECT_EQ(le_u64(bytes_, c + 34), sample_.messages.back().log_time);
    ASSERT_EQ(le_u32(bytes_, c + 42), 3u * 10u);  // map byte length: 3 x (uint16 + uint64)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(le_u64(bytes_, c + 46 + 10 * k + 2), 500u);
    return;
  }
  FAIL() << "no Statistics record in the summary";
}

TEST_F(McapLayout, ChunkIndexesPointAtChunksAndTheirMessageIndexes) {
  std::size_t chunks = 0;
  uint64_t indexed_messages = 0;
  for (const auto& r : walk(bytes_, summary_start_, summary_offset_start_)) {
    if (r.opcode != 0x08) continue;
    ++chunks;
    uint64_t c = r.offset + 9;
    const uint64_t chunk_start = le_u64(bytes_, c + 16);
    const uint64_t chunk_length = le_u64(bytes_, c + 24);
    ASSERT_EQ(bytes_.at(chunk_start), 0x06);
    EXPECT_EQ(le_u64(bytes_, chunk_start + 1) + 9, chunk_length);
    const uint32_t map_len = le_u32(bytes_, c + 32);
    uint64_t expected_index_offset = chunk_start + chunk_length;  // indexes follow the chunk
    for (uint64_t e = c + 36; e < c + 36 + map_len; e += 10) {
      const uint16_t channel = le_u16(bytes_, e);
      const uint64_t at = le_u64(bytes_, e + 2);
      EXPECT_EQ(at, expected_index_offset);
      ASSERT_EQ(bytes_.at(at), 0x07);
      EXPECT_EQ(le_u16(bytes_, at + 9), channel);
      const uint32_t entries_len = le_u32(bytes_, at + 11);
      indexed_messages += entries_len / 16;
      // Every entry points at a Message record of this channel inside the chunk, which is
      // checkable directly only without compression; here check the entry layout.
      EXPECT_EQ(entries_len % 16, 0u);
      expected_index_offset = at + 9 + le_u64(bytes_, at + 1);
    }
    const uint64_t index_length = le_u64(bytes_, c + 36 + map_len);
    EXPECT_EQ(chunk_start + chunk_length + index_length, expected_index_offset);
    const uint32_t comp_len = le_u32(bytes_, c + 44 + map_len);
    EXPECT_EQ(std::string(bytes_.begin() + c + 48 + map_len, bytes_.begin() + c + 48 + map_len + comp_len),
              "zstd");
  }
  EXPECT_GT(chunks, 1u);
  EXPECT_EQ(indexed_messages, 1500u);
}

TEST(McapLayoutUncompressed, MessageIndexEntriesPointAtMessageRecords) {
  // With compression "" the chunk's records lie in the file as they are, so every
  // MessageIndex entry can be followed to its Message record by hand.
  test::ScratchDir dir;
  const std::string path = dir.file("plain.mcap");
  WriterOptions options;
  options.compression = Compression::none;
  options.chunk_size = 4096;
  const auto sample = test::write_sample(path, options, 300);
  const auto b = test::read_bytes(path);
  const uint64_t summary_start = le_u64(b, b.size() - 8 - 29 + 9);
  std::size_t checked = 0;
  uint64_t records_start = 0;
  for (const auto& r : walk(b, 8, summary_start)) {
    if (r.opcode == 0x06) {
      const uint64_t c = r.offset + 9;
      const uint32_t comp_len = le_u32(b, c + 28);
      ASSERT_EQ(comp_len, 0u);  // compression ""
      records_start = c + 32 + 8;
      EXPECT_EQ(le_u64(b, c + 32), le_u64(b, c + 16));  // records size == uncompressed size
      EXPECT_EQ(le_u32(b, c + 24), crc_of(b, records_start, records_start + le_u64(b, c + 16)));
    } else if (r.opcode == 0x07) {
      const uint16_t channel = le_u16(b, r.offset + 9);
      const uint32_t n = le_u32(b, r.offset + 11);
      for (uint64_t e = r.offset + 15; e < r.offset + 15 + n; e += 16) {
        const uint64_t log_time = le_u64(b, e);
        const uint64_t msg = records_start + le_u64(b, e + 8);
        ASSERT_EQ(b.at(msg), 0x05);
        EXPECT_EQ(le_u16(b, msg + 9), channel);
        EXPECT_EQ(le_u64(b, msg + 15), log_time);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, sample.messages.size());
}

}  // namespace
}  // namespace mechsim::record
