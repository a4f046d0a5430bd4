// Plain data shared by the MCAP writer, reader and recovery: what an MCAP file holds,
// independent of DDS (messages are opaque CDR byte blobs here).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mechsim::record {

// Chunk compression. MCAP names them "" (none), "zstd" and "lz4" (LZ4 frame format).
enum class Compression { none, zstd, lz4 };

// The name MCAP stores in Chunk and ChunkIndex records for `compression`.
std::string compression_name(Compression compression);

// A malformed, corrupted or unreadable MCAP file (bad magic, CRC mismatch, a record that
// runs past its container, a decompression failure). The message names the byte offset.
class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a reader accepts from a chunk before it decompresses anything: a file from elsewhere
// may claim any size, so the claim itself is bounded (docs/recording.md, "Reading files
// from elsewhere"). A chunk over either bound is refused as damaged, naming its offset.
struct ChunkLimits {
  // Uncompressed bytes of one chunk. The recorder closes a chunk at 1 MiB (WriterOptions::
  // chunk_size) plus at most one message; 64 MiB leaves room for writers with bigger chunks.
  uint64_t max_chunk_size = uint64_t(64) << 20;
  // Uncompressed / compressed bytes, for chunks over `expansion_floor`. The recorder's most
  // compressible data, a machine at rest (constant payloads of up to 64 doubles), reaches
  // 57:1 with zstd level 1 and 30:1 with lz4 (docs/recording.md "Reading files from
  // elsewhere"); 1000:1 leaves 17x room. Only degenerate content gets past it: 1 MiB of zeros
  // is 19000:1 with zstd (its run-length blocks allow 32768:1) and 253:1 with lz4.
  uint64_t max_expansion = 1000;
  // Chunks claiming up to this size pass whatever their ratio: everything the recorder
  // writes (1 MiB plus one message of at most 64 KiB) costs little memory however it packs.
  uint64_t expansion_floor = uint64_t(2) << 20;
};

// The reader's own accounting of chunk decompression, for the memory and time budget.
struct ReadAccounting {
  uint64_t chunks_opened = 0;      // decompression attempts (sound or not)
  uint64_t bytes_decompressed = 0; // output produced by the decoders, summed
  uint64_t largest_chunk_buffers = 0;  // compressed record + uncompressed buffer of one chunk
};

struct Schema {
  uint16_t id = 0;        // never 0 (0 means "no schema" in MCAP)
  std::string name;       // e.g. "mechsim::msg::CamState"
  std::string encoding;   // "omgidl" for mechsim
  std::string data;       // the schema text (IDL)
  bool operator==(const Schema&) const = default;
};

struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  // "cdr" for mechsim
  std::map<std::string, std::string> metadata;
  bool operator==(const Channel&) const = default;
};

// The MCAP Statistics record (attachments and metadata are never written by mechsim).
struct Statistics {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0;
  uint32_t attachment_count = 0;
  uint32_t metadata_count = 0;
  uint32_t chunk_count = 0;
  uint64_t message_start_time = 0;  // earliest log time [ns]; 0 if there are no messages
  uint64_t message_end_time = 0;    // latest log time [ns]; 0 if there are no messages
  std::map<uint16_t, uint64_t> channel_message_counts;
  bool operator==(const Statistics&) const = default;
};

// A message as handed to a reader callback: `data` points into the reader's chunk buffer
// and is valid only during the callback.
struct MessageView {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;      // [ns] wall time when the recorder received it
  uint64_t publish_time = 0;  // [ns] simulated time of the sample (mechsim convention)
  std::span<const std::byte> data;
};

// An owning copy of a message.
struct Message {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  std::vector<std::byte> data;
  bool operator==(const Message&) const = default;
};

// Where a chunk lies in the file and what it covers (the MCAP ChunkIndex fields).
struct ChunkInfo {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t chunk_start_offset = 0;  // file offset of the Chunk record's opcode
  uint64_t chunk_length = 0;        // whole record: opcode + length prefix + content
  std::map<uint16_t, uint64_t> message_index_offsets;  // channel -> MessageIndex record offset
  uint64_t message_index_length = 0;
  std::string compression;
  uint64_t compressed_size = 0;
  uint64_t uncompressed_size = 0;
  bool operator==(const ChunkInfo&) const = default;
};

// One group of same-opcode records in the summary section (MCAP SummaryOffset record).
struct SummaryOffset {
  uint8_t group_opcode = 0;
  uint64_t group_start = 0;
  uint64_t group_length = 0;
  bool operator==(const SummaryOffset&) const = default;
};

}  // namespace mechsim::record
