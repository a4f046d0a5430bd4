// Writing then reading a recording gives back exactly what was written, with each
// compression, through the summary and (via recover(), which rebuilds from a scan of the
// data section) through the data section alone.
#include <gtest/gtest.h>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_writer.h"
#include "record_test_support.h"

namespace mechsim::record {
namespace {

using test::ScratchDir;

class McapRoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(McapRoundTrip, MessagesSchemasChannelsAndStatisticsSurvive) {
  ScratchDir dir;
  const std::string path = dir.file("round_trip.mcap");
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_size = 16 * 1024;  // many chunks from a few thousand messages
  options.library = "mechsim-test";
  const auto written = test::write_sample(path, options, 3000);

  const McapReader reader(path);
  EXPECT_TRUE(reader.complete());
  EXPECT_FALSE(reader.truncated());
  EXPECT_EQ(reader.library(), "mechsim-test");
  EXPECT_EQ(reader.profile(), "");
  ASSERT_EQ(reader.schemas().size(), 2u);
  for (const auto& s : written.schemas) EXPECT_EQ(reader.schemas().at(s.id), s);
  ASSERT_EQ(reader.channels().size(), 3u);
  for (const auto& c : written.channels) EXPECT_EQ(reader.channels().at(c.id), c);

  // Log times increase with write order, so the reader's order is the write order.
  const std::vector<Message> read = reader.read_messages();
  ASSERT_EQ(read.size(), written.messages.size());
  EXPECT_TRUE(read == written.messages);

  const Statistics& stats = reader.statistics();
  EXPECT_EQ(stats.message_count, 3000u);
  EXPECT_EQ(stats.schema_count, 2u);
  EXPECT_EQ(stats.channel_count, 3u);
  EXPECT_EQ(stats.chunk_count, reader.chunks().size());
  EXPECT_GT(stats.chunk_count, 3u) << "the test needs several chunks";
  EXPECT_EQ(stats.message_start_time, written.messages.front().log_time);
  EXPECT_EQ(stats.message_end_time, written.messages.back().log_time);
  for (const auto& c : written.channels) EXPECT_EQ(stats.channel_message_counts.at(c.id), 1000u);
  const std::string expected_compression = compression_name(GetParam());
  for (const auto& chunk : reader.chunks()) EXPECT_EQ(chunk.compression, expected_compression);
  EXPECT_TRUE(reader.verify().empty());

  // The scan path (used for truncated files) must see the same file the summary describes.
  const std::string rebuilt = dir.file("rebuilt.mcap");
  const RecoveryReport report = recover(path, rebuilt);
  EXPECT_TRUE(report.input_complete);
  EXPECT_EQ(report.messages, 3000u);
  EXPECT_EQ(report.chunks, stats.chunk_count);
  EXPECT_EQ(report.chunks_dropped, 0u);
  const McapReader again(rebuilt);
  EXPECT_TRUE(again.complete());
  EXPECT_EQ(again.statistics(), stats);
  EXPECT_EQ(again.chunks(), reader.chunks());  // chunks are copied to the same offsets
  EXPECT_TRUE(again.read_messages() == written.messages);
  // Same data section byte for byte => identical files.
  EXPECT_EQ(test::read_bytes(rebuilt), test::read_bytes(path));
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapRoundTrip,
                         ::testing::Values(Compression::none, Compression::zstd, Compression::lz4),
                         [](const auto& info) {
                           const std::string n = compression_name(info.param);
                           return n.empty() ? std::string("none") : n;
                         });

TEST(McapRoundTrip, MessagesComeOutInLogTimeOrderWithinAChunk) {
  // Log time is the receive wall time: with several listener threads it can go backwards
  // between writes. Readers expect log-time order within a chunk.
  ScratchDir dir;
  const std::string path = dir.file("unordered.mcap");
  {
    McapWriter writer(path, {});
    const uint16_t ch = writer.add_channel(0, "t", "cdr");
    const std::byte payload[1] = {std::byte{7}};
    for (uint64_t t : {50u, 30u, 40u, 30u, 10u}) writer.write(ch, static_cast<uint32_t>(t), t, t + 1, payload);
  }
  const McapReader reader(path);
  std::vector<std::pair<uint64_t, uint32_t>> seen;
  reader.for_each_message([&](const MessageView& m) { seen.emplace_back(m.log_time, m.sequence); });
  const std::vector<std::pair<uint64_t, uint32_t>> expected{{10, 10}, {30, 30}, {30, 30}, {40, 40}, {50, 50}};
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(reader.statistics().message_start_time, 10u);
  EXPECT_EQ(reader.statistics().message_end_time, 50u);
  ASSERT_EQ(reader.chunks().size(), 1u);
  EXPECT_EQ(reader.chunks()[0].message_start_time, 10u);
  EXPECT_EQ(reader.chunks()[0].message_end_time, 50u);
}

TEST(McapRoundTrip, EmptyRecordingIsAValidFile) {
  ScratchDir dir;
  const std::string path = dir.file("empty.mcap");
  McapWriter(path, {}).close();
  const McapReader reader(path);
  EXPECT_TRUE(reader.complete());
  EXPECT_EQ(reader.statistics().message_count, 0u);
  EXPECT_TRUE(reader.chunks().empty());
  EXPECT_TRUE(reader.read_messages().empty());
}

}  // namespace
}  // namespace mechsim::record
