// Opening a Chunk record: bounds, decompression, CRC check, and the records inside.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "file_io.h"
#include "records.h"

namespace mechsim::record::detail {

// "Chunk at offset N": how every refusal names a chunk.
std::string chunk_where(uint64_t chunk_offset);

// A Chunk record read from the file: `header.records` views `raw`; `records` holds the
// uncompressed records (empty if only the header was read).
struct OpenedChunk {
  Buffer raw;
  ChunkHeader header;
  Buffer records;
  OpenedChunk() = default;
  OpenedChunk(const OpenedChunk&) = delete;  // header.records views raw
  OpenedChunk& operator=(const OpenedChunk&) = delete;
  OpenedChunk(OpenedChunk&&) = default;       // a moved vector keeps its storage
  OpenedChunk& operator=(OpenedChunk&&) = default;
};

// Reads the Chunk record at `offset` that is `length` bytes long as a whole (from the scan
// or from the ChunkIndex) and decompresses it. Throws McapError naming the chunk's offset
// when the record is not a Chunk, its own length field disagrees with `length`, it is over
// `limits` (checked before reading or allocating), it does not decompress to exactly the
// size it claims, or its CRC (unless 0, "not available") does not match. `accounting`
// counts the attempt, the bytes decoded and the buffers held. `pass` (if given) sums one
// pass over the file's chunks: a chunk that would take the claims past limits.max_expansion
// x the chunk records so far + one chunk is refused, so that many small chunks (each under
// the expansion floor) cannot multiply a small file either. Relative to the chunks, not the
// file, so that recover()'s output (the same chunks) passes where its input did.
struct PassBudget {
  uint64_t claimed = 0;        // uncompressed sizes of the chunks admitted so far
  uint64_t chunk_records = 0;  // their record sizes
};
// Adds a chunk of `record_length` bytes claiming `claimed` to `pass` if the claims stay
// within the budget; false (nothing added) otherwise.
bool admit(PassBudget& pass, uint64_t record_length, uint64_t claimed, const ChunkLimits& limits);
OpenedChunk read_chunk(const InputFile& file, uint64_t offset, uint64_t length,
                       const ChunkLimits& limits, ReadAccounting& accounting,
                       PassBudget* pass = nullptr);

// What a chunk's records hold: its messages in record order (views into `records`) with
// their offsets, and any Schema/Channel records written inside it.
struct ChunkContents {
  std::vector<MessageView> messages;
  std::vector<uint64_t> message_offsets;  // of each Message record in `records`
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
};
ChunkContents parse_chunk_records(const Buffer& records, uint64_t chunk_offset);

}  // namespace mechsim::record::detail
