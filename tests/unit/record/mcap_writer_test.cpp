// Writer behaviour that the format tests do not cover: argument checks, when chunks are
// closed, and that a SIGKILLed recorder leaves its completed chunks readable.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_writer.h"
#include "record_test_support.h"

namespace mechsim::record {
namespace {

const std::byte kPayload[3] = {std::byte{1}, std::byte{2}, std::byte{3}};

TEST(McapWriter, UnwritablePathIsNamedInTheError) {
  try {
    McapWriter writer("/nonexistent-dir/x.mcap", {});
    FAIL() << "no error for an unwritable path";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.mcap"), std::string::npos) << e.what();
  }
}

TEST(McapWriter, UnknownIdsAndUseAfterCloseAreRefused) {
  test::ScratchDir dir;
  McapWriter writer(dir.file("w.mcap"), {});
  EXPECT_THROW(writer.add_channel(5, "t", "cdr"), std::invalid_argument);
  const uint16_t schema = writer.add_schema("S", "omgidl", "struct S { long a; };");
  EXPECT_EQ(schema, 1u);  // 0 is reserved for "no schema"
  const uint16_t ch = writer.add_channel(schema, "t", "cdr");
  EXPECT_THROW(writer.write(ch + 1, 0, 0, 0, kPayload), std::invalid_argument);
  writer.write(ch, 0, 0, 0, kPayload);
  writer.close();
  writer.close();  // idempotent
  EXPECT_THROW(writer.write(ch, 0, 0, 0, kPayload), std::logic_error);
}

TEST(McapWriter, ChunkClosesAtChunkSize) {
  test::ScratchDir dir;
  WriterOptions options;
  options.chunk_size = 1000;
  options.max_chunk_interval = std::chrono::hours(1);
  McapWriter writer(dir.file("w.mcap"), options);
  const uint16_t ch = writer.add_channel(0, "t", "cdr");
  // A Message record is 9 + 22 + 3 = 34 bytes; the 30th brings the chunk to 1020 >= 1000.
  for (int i = 0; i < 29; ++i) writer.write(ch, i, i, i, kPayload);
  EXPECT_EQ(writer.chunk_count(), 0u);
  writer.write(ch, 29, 29, 29, kPayload);
  EXPECT_EQ(writer.chunk_count(), 1u);
  EXPECT_EQ(writer.message_count(), 30u);
  EXPECT_EQ(writer.channel_message_counts().at(ch), 30u);
}

TEST(McapWriter, MaxChunkIntervalZeroClosesEveryChunkAtOnce) {
  // The interval test without a clock dependence: 0 means "always due".
  test::ScratchDir dir;
  WriterOptions options;
  options.max_chunk_interval = std::chrono::milliseconds(0);
  McapWriter writer(dir.file("w.mcap"), options);
  const uint16_t ch = writer.add_channel(0, "t", "cdr");
  for (int i = 0; i < 5; ++i) writer.write(ch, i, i, i, kPayload);
  EXPECT_EQ(writer.chunk_count(), 5u);
  EXPECT_FALSE(writer.flush_if_due());  // nothing open
}

TEST(McapWriter, FlushIfDueLeavesAYoungChunkOpenAndFlushWritesIt) {
  test::ScratchDir dir;
  WriterOptions options;
  options.max_chunk_interval = std::chrono::hours(1);
  McapWriter writer(dir.file("w.mcap"), options);
  const uint16_t ch = writer.add_channel(0, "t", "cdr");
  writer.write(ch, 0, 0, 0, kPayload);
  EXPECT_FALSE(writer.flush_if_due());
  EXPECT_EQ(writer.chunk_count(), 0u);
  const uint64_t before = writer.bytes_written();
  writer.flush();
  EXPECT_EQ(writer.chunk_count(), 1u);
  EXPECT_GT(writer.bytes_written(), before);
}

TEST(McapWriter, ChannelAddedMidRecordingPrecedesItsChunk) {
  test::ScratchDir dir;
  const std::string path = dir.file("w.mcap");
  {
    WriterOptions options;
    options.chunk_size = 200;
    McapWriter writer(path, options);
    const uint16_t a = writer.add_channel(0, "a", "cdr");
    for (int i = 0; i < 20; ++i) writer.write(a, i, i, i, kPayload);
    writer.write(a, 20, 20, 20, kPayload);  // an open chunk when the next channel arrives
    const uint16_t b = writer.add_channel(0, "b", "cdr");
    writer.write(b, 0, 21, 21, kPayload);
  }
  // Cut right after the chunk holding "b"'s message and drop the tail: the scan must
  // still know channel b, so its Channel record came before that chunk.
  const McapReader full(path);
  const ChunkInfo last = full.chunks().back();
  const auto bytes = test::read_bytes(path);
  const std::string cut = dir.file("cut.mcap");
  test::write_bytes(cut, bytes.data(), last.chunk_start_offset + last.chunk_length);
  const McapReader reader(cut);
  EXPECT_TRUE(reader.truncated());
  ASSERT_EQ(reader.channels().size(), 2u);
  EXPECT_EQ(reader.statistics().message_count, 22u);
}

TEST(McapWriter, SigkilledRecorderLeavesItsCompletedChunksReadable) {
  test::ScratchDir dir;
  const std::string path = dir.file("killed.mcap");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The recorder: two completed chunks (50 + 30 messages), then 7 messages in an open
    // chunk, then killed without any chance to clean up.
    WriterOptions options;
    options.chunk_size = 1 << 30;
    options.max_chunk_interval = std::chrono::hours(1);
    McapWriter writer(path, options);
    const uint16_t s = writer.add_schema("S", "omgidl", "struct S { long a; };");
    const uint16_t ch = writer.add_channel(s, "t", "cdr");
    uint32_t seq = 0;
    for (int i = 0; i < 50; ++i, ++seq) writer.write(ch, seq, seq, seq, kPayload);
    writer.flush();
    for (int i = 0; i < 30; ++i, ++seq) writer.write(ch, seq, seq, seq, kPayload);
    writer.flush();
    for (int i = 0; i < 7; ++i, ++seq) writer.write(ch, seq, seq, seq, kPayload);
    ::kill(::getpid(), SIGKILL);
    ::_exit(3);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  const McapReader reader(path);
  EXPECT_TRUE(reader.truncated());
  EXPECT_EQ(reader.chunks().size(), 2u);
  const auto messages = reader.read_messages();
  ASSERT_EQ(messages.size(), 80u);
  for (uint32_t i = 0; i < 80; ++i) EXPECT_EQ(messages[i].sequence, i);

  const std::string out = dir.file("recovered.mcap");
  const RecoveryReport report = recover(path, out);
  EXPECT_EQ(report.messages, 80u);
  EXPECT_EQ(report.schemas, 1u);
  EXPECT_EQ(report.channels, 1u);
  const McapReader recovered(out);
  EXPECT_TRUE(recovered.complete());
  EXPECT_EQ(recovered.statistics().message_count, 80u);
}

}  // namespace
}  // namespace mechsim::record
