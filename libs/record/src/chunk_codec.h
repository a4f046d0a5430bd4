// Opening a Chunk record: decompression, CRC check, and the records inside.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "records.h"

namespace mechsim::record::detail {

// The uncompressed records of a chunk. Throws McapError naming the chunk's file offset on
// a CRC mismatch (unless the stored CRC is 0, "not available") or a decompression failure.
Buffer open_chunk(const ChunkHeader& header, uint64_t chunk_offset);

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
