// Corrupted bytes are detected by the CRCs, never silently read as data.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdint>
#include <string>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_writer.h"
#include "record_test_support.h"

namespace mechsim::record {
namespace {

class McapCorruption : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.file("clean.mcap");
    WriterOptions options;
    // Uncompressed, so a flipped byte still decompresses and only the CRC can catch it.
    options.compression = Compression::none;
    options.chunk_size = 4096;
    sample_ = test::write_sample(path_, options, 600);
    bytes_ = test::read_bytes(path_);
    const McapReader reader(path_);
    chunks_ = reader.chunks();
    ASSERT_GE(chunks_.size(), 3u);
  }
  // Writes the file with one payload byte of chunk `k` flipped; returns its path.
  std::string with_flipped_chunk_byte(std::size_t k) {
    auto bytes = bytes_;
    const ChunkInfo& c = chunks_.at(k);
    bytes.at(c.chunk_start_offset + c.chunk_length - 3) ^= 0x40;  // last message's payload
    const std::string path = dir_.file("flipped.mcap");
    test::write_bytes(path, bytes.data(), bytes.size());
    return path;
  }

  test::ScratchDir dir_;
  std::string path_;
  test::SampleRecording sample_;
  std::vector<uint8_t> bytes_;
  std::vector<ChunkInfo> chunks_;
};

TEST_F(McapCorruption, ChunkCrcMismatchIsReportedWhenReading) {
  const McapReader reader(with_flipped_chunk_byte(1));  // the summary is intact
  EXPECT_TRUE(reader.complete());
  try {
    reader.read_messages();
    FAIL() << "a corrupt chunk was read without complaint";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("CRC mismatch"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(std::to_string(chunks_[1].chunk_start_offset)),
              std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(reader.read_chunk(chunks_[0]));
  EXPECT_THROW(reader.read_chunk(chunks_[1]), McapError);
}

TEST_F(McapCorruption, VerifyReportsChunkAndDataSectionCrc) {
  const McapReader reader(with_flipped_chunk_byte(2));
  const auto problems = reader.verify();
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(problems[0].find("data section CRC mismatch"), std::string::npos) << problems[0];
  EXPECT_NE(problems[1].find("CRC mismatch"), std::string::npos) << problems[1];
  EXPECT_TRUE(McapReader(path_).verify().empty());
}

TEST_F(McapCorruption, RecoveryDropsTheCorruptChunkOnly) {
  const std::string out = dir_.file("recovered.mcap");
  const RecoveryReport report = recover(with_flipped_chunk_byte(1), out);
  EXPECT_EQ(report.chunks_dropped, 1u);
  EXPECT_EQ(report.chunks, chunks_.size() - 1);
  const McapReader clean(path_);
  const std::size_t lost = clean.read_chunk(chunks_[1]).size();
  const McapReader recovered(out);
  EXPECT_EQ(recovered.statistics().message_count, sample_.messages.size() - lost);
  EXPECT_TRUE(recovered.verify().empty());
}

TEST_F(McapCorruption, SummaryCrcMismatchIsRefusedAndRecoverable) {
  auto bytes = bytes_;
  const uint64_t summary_start = test::le_u64(bytes, bytes.size() - 8 - 29 + 9);
  bytes.at(summary_start + 20) ^= 0x01;
  const std::string path = dir_.file("bad_summary.mcap");
  test::write_bytes(path, bytes.data(), bytes.size());
  try {
    McapReader reader(path);
    FAIL() << "a corrupt summary was accepted";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("summary CRC mismatch"), std::string::npos) << e.what();
  }
  const std::string out = dir_.file("rebuilt.mcap");
  EXPECT_EQ(recover(path, out).messages, sample_.messages.size());
  EXPECT_TRUE(McapReader(out).read_messages() == sample_.messages);
}

// A summary without CRC (0: not computed, as the spec allows) is taken as it is; a
// Statistics message count of 2^57 must not become an allocation (read_messages reserved
// it: ASan's allocation-size-too-big, found by tests/fuzz/mcap_fuzz). The messages are read.
TEST_F(McapCorruption, ImplausibleMessageCountInAnUncheckedSummaryIsNotAllocated) {
  auto bytes = bytes_;
  const std::size_t footer = bytes.size() - 8 - 29;
  const uint64_t summary_start = test::le_u64(bytes, footer + 9);
  for (int i = 0; i < 4; ++i) bytes.at(footer + 9 + 16 + i) = 0;  // summary_crc = 0
  std::size_t statistics = 0;
  for (std::size_t at = summary_start; at < footer; at += 9 + test::le_u64(bytes, at + 1))
    if (bytes.at(at) == 0x0B) statistics = at;
  ASSERT_NE(statistics, 0u);
  ASSERT_EQ(test::le_u64(bytes, statistics + 9), sample_.messages.size());
  bytes.at(statistics + 9 + 7) = 0x02;  // message_count += 2^57
  const std::string path = dir_.file("big_count.mcap");
  test::write_bytes(path, bytes.data(), bytes.size());
  const McapReader reader(path);
  EXPECT_EQ(reader.statistics().message_count, (uint64_t{1} << 57) + sample_.messages.size());
  EXPECT_TRUE(reader.read_messages() == sample_.messages);
}

TEST_F(McapCorruption, NotAnMcapFileIsRefused) {
  auto bytes = bytes_;
  bytes[1] = 'X';
  const std::string path = dir_.file("no_magic.mcap");
  test::write_bytes(path, bytes.data(), bytes.size());
  EXPECT_THROW(McapReader{path}, McapError);
  EXPECT_THROW(McapReader{dir_.file("missing.mcap")}, McapError);
}

TEST(McapCorruptionCompressed, FlippedCompressedByteIsDetected) {
  // In a zstd chunk a flipped byte breaks either the frame or the CRC: both are errors.
  test::ScratchDir dir;
  const std::string path = dir.file("z.mcap");
  WriterOptions options;
  options.chunk_size = 4096;
  test::write_sample(path, options, 600);
  auto bytes = test::read_bytes(path);
  const ChunkInfo chunk = McapReader(path).chunks().at(1);
  bytes.at(chunk.chunk_start_offset + chunk.chunk_length - chunk.compressed_size / 2) ^= 0x40;
  const std::string bad = dir.file("z_bad.mcap");
  test::write_bytes(bad, bytes.data(), bytes.size());
  EXPECT_THROW(McapReader(bad).read_messages(), McapError);
}

// A chunk header claiming a far larger uncompressed size than its data holds is refused
// without allocating the claim (decompression allocated it up front: 3.6 GB, found by
// tests/fuzz/mcap_fuzz); one claiming less than the data holds is refused as well.
class McapClaimedChunkSize : public ::testing::TestWithParam<Compression> {
 protected:
  // The file with chunk 1's uncompressed_size replaced; returns its path.
  std::string with_claimed_size(uint64_t claimed) {
    options_.compression = GetParam();
    options_.chunk_size = 4096;
    const std::string path = dir_.file("clean.mcap");
    test::write_sample(path, options_, 600);
    auto bytes = test::read_bytes(path);
    chunk_ = McapReader(path).chunks().at(1);
    const std::size_t size_at = chunk_.chunk_start_offset + 1 + 8 + 8 + 8;
    for (int i = 0; i < 8; ++i) bytes.at(size_at + i) = uint8_t(claimed >> (8 * i));
    const std::string bad = dir_.file("claimed.mcap");
    test::write_bytes(bad, bytes.data(), bytes.size());
    return bad;
  }
  std::string error_reading(const std::string& path) {
    try {
      McapReader(path).read_chunk(chunk_);
    } catch (const McapError& e) {
      return e.what();
    }
    return "(no error)";
  }

  test::ScratchDir dir_;
  WriterOptions options_;
  ChunkInfo chunk_;
};

long peak_rss_kib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

TEST_P(McapClaimedChunkSize, AClaimOfGigabytesIsRefusedWithoutAllocatingIt) {
  const uint64_t claimed = 3640656057;
  const std::string path = with_claimed_size(claimed);
  const long rss_before = peak_rss_kib();
  const std::string error = error_reading(path);
  EXPECT_NE(error.find("claims " + std::to_string(claimed) + " bytes uncompressed"), std::string::npos) << error;
  // The old code touched the whole claim; the real chunk is 4 KiB. 256 MiB is room for any
  // allocator noise and far below the claim.
  EXPECT_LT(peak_rss_kib() - rss_before, 256 * 1024) << "the claimed size was allocated";
}

TEST_P(McapClaimedChunkSize, AClaimSmallerThanTheDataIsRefused) {
  const std::string path = with_claimed_size(100);
  const std::string error = error_reading(path);
  EXPECT_NE(error.find("larger than the chunk says (100 bytes)"), std::string::npos) << error;
}

INSTANTIATE_TEST_SUITE_P(Codecs, McapClaimedChunkSize,
                         ::testing::Values(Compression::zstd, Compression::lz4),
                         [](const auto& info) { return compression_name(info.param); });

}  // namespace
}  // namespace mechsim::record
