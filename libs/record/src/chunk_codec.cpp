#include "chunk_codec.h"

#include <algorithm>
#include <cstdio>

#include "compression.h"
#include "crc32.h"

namespace mechsim::record::detail {
namespace {

std::string hex32(uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", v);
  return text;
}

}  // namespace

Buffer open_chunk(const ChunkHeader& header, uint64_t chunk_offset) {
  const std::string where = "Chunk at offset " + std::to_string(chunk_offset);
  Buffer records = decompress(header.compression, header.records, header.uncompressed_size, where);
  if (header.uncompressed_crc != 0) {
    const uint32_t crc = crc32_update(0, records);
    if (crc != header.uncompressed_crc)
      throw McapError(where + ": CRC mismatch (stored " + hex32(header.uncompressed_crc) +
                      ", computed " + hex32(crc) + ")");
  }
  return records;
}

ChunkContents parse_chunk_records(const Buffer& records, uint64_t chunk_offset) {
  ChunkContents contents;
  const std::string where = "Chunk at offset " + std::to_string(chunk_offset);
  for_each_record(std::span<const uint8_t>(records), where,
                  [&](uint8_t opcode, std::span<const uint8_t> content, uint64_t at) {
                    switch (opcode) {
                      case op::message:
                        contents.messages.push_back(decode_message(content, chunk_offset));
                        contents.message_offsets.push_back(at);
                        break;
                      case op::schema: contents.schemas.push_back(decode_schema(content, chunk_offset)); break;
                      case op::channel: contents.channels.push_back(decode_channel(content, chunk_offset)); break;
                      default: break;  // nothing else belongs in a chunk; ignore what later specs add
                    }
                  });
  return contents;
}

}  // namespace mechsim::record::detail
