// An MCAP writer for recordings: one Schema per IDL type, one Channel per topic, messages
// as opaque CDR blobs in compressed chunks, with message indexes, a summary section
// (schemas, channels, statistics, chunk indexes), summary offsets and footer.
//
// Crash safety: Schema and Channel records go to the data section (outside chunks) as
// soon as they are added, before any chunk that uses them; every finished chunk is written
// and flushed to the kernel at once, so a process killed at any point (SIGKILL included)
// leaves a file whose complete chunks are readable (McapReader) and recoverable into a
// complete file (recover()). At most the open chunk is lost: it is closed when it reaches
// `chunk_size` bytes or is `max_chunk_interval` old. See docs/recording.md.
//
// Thread safety: every public member locks one mutex, so DDS listener threads may write
// concurrently.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>

#include "mechsim/record/mcap_types.h"

namespace mechsim::record {

// What happens after each chunk is written.
enum class SyncMode {
  flush,      // fflush: the chunk is in the kernel; survives a crash of the process (default)
  data_sync,  // fflush + fdatasync: survives a crash of the machine, costs a disk round trip
};

struct WriterOptions {
  Compression compression = Compression::zstd;
  std::size_t chunk_size = 1 << 20;  // uncompressed bytes that close a chunk
  // A chunk whose first message is older than this (wall time) is closed by the next
  // write() or flush_if_due(): bounds what a crash can lose in a slow run.
  std::chrono::milliseconds max_chunk_interval{1000};
  SyncMode sync = SyncMode::flush;
  std::string profile = "";          // MCAP Header profile ("" : no well-known profile)
  std::string library = "mechsim";   // MCAP Header library
};

class McapWriter {
 public:
  // Creates (truncates) `path` and writes the magic and Header. Throws std::runtime_error
  // naming the path if the file cannot be created.
  McapWriter(const std::string& path, WriterOptions options = {});
  ~McapWriter();  // close(), swallowing errors (call close() to see them)
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // Ids are assigned from 1 upwards. The record is written to the data section and flushed.
  uint16_t add_schema(const std::string& name, const std::string& encoding,
                      const std::string& data);
  // schema_id 0 means "no schema"; any other id must come from add_schema (else
  // std::invalid_argument).
  uint16_t add_channel(uint16_t schema_id, const std::string& topic,
                       const std::string& message_encoding,
                       const std::map<std::string, std::string>& metadata = {});

  // Appends a message to the open chunk; closes the chunk if it is full or due. Throws
  // std::invalid_argument for an unknown channel, std::logic_error after close().
  void write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns,
             uint64_t publish_time_ns, std::span<const std::byte> data);

  // Writes the open chunk now (if it holds anything) and flushes.
  void flush();
  // flush() if the open chunk is older than max_chunk_interval; for a recorder's timer, so
  // that a topic that goes quiet does not keep its last messages in memory. Returns
  // whether a chunk was written.
  bool flush_if_due();

  // Writes the last chunk, DataEnd, the summary section, SummaryOffsets, Footer and magic,
  // and closes the file. Idempotent. Throws std::runtime_error on I/O failure.
  void close();

  // Statistics of what was written so far (messages in the open chunk included).
  uint64_t message_count() const;
  std::map<uint16_t, uint64_t> channel_message_counts() const;
  uint64_t chunk_count() const;     // chunks written to the file
  uint64_t bytes_written() const;   // file size so far (the open chunk excluded)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mechsim::record
