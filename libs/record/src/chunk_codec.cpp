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

bool admit(PassBudget& pass, uint64_t record_length, uint64_t claimed, const ChunkLimits& limits) {
  // claimed <= max_chunk_size (checked first) and records <= the file size: no overflow.
  const uint64_t records = pass.chunk_records + record_length;
  if (pass.claimed + claimed > limits.max_expansion * records + limits.max_chunk_size) return false;
  pass.claimed += claimed;
  pass.chunk_records = records;
  return true;
}

std::string chunk_where(uint64_t chunk_offset) { return "Chunk at offset " + std::to_string(chunk_offset); }

OpenedChunk read_chunk(const InputFile& file, uint64_t offset, uint64_t length,
                       const ChunkLimits& limits, ReadAccounting& accounting, PassBudget* pass) {
  const std::string where = chunk_where(offset);
  // A compressed record is at most a little larger than its contents (zstd/lz4 bounds are
  // below 1/64 extra) plus the header fields: larger records are refused before reading.
  const uint64_t max_record = limits.max_chunk_size + limits.max_chunk_size / 64 + 4096;
  if (length > max_record)
    throw McapError(where + ": record of " + std::to_string(length) +
                    " bytes, more than the reader's chunk limit allows (" +
                    std::to_string(max_record) + " bytes)");
  OpenedChunk chunk;
  chunk.raw = file.read(offset, length);
  accounting.largest_chunk_buffers = std::max<uint64_t>(accounting.largest_chunk_buffers, chunk.raw.size());
  if (chunk.raw.size() < kRecordPrefixSize || chunk.raw[0] != op::chunk)
    throw McapError(where + ": no Chunk record there (opcode " +
                    (chunk.raw.empty() ? std::string("none") : opcode_name(chunk.raw[0])) + ")");
  uint64_t own_length = 0;
  for (int i = 0; i < 8; ++i) own_length |= uint64_t(chunk.raw[1 + i]) << (8 * i);
  if (own_length != length - kRecordPrefixSize)
    throw McapError(where + ": record length field says " + std::to_string(own_length) +
                    " bytes, the index says " + std::to_string(length - kRecordPrefixSize));
  chunk.header = decode_chunk(std::span<const uint8_t>(chunk.raw).subspan(kRecordPrefixSize), offset);
  ++accounting.chunks_opened;
  check_claim(chunk.header.compression, chunk.header.records.size(), chunk.header.uncompressed_size,
              limits, where);
  if (pass && !admit(*pass, length, chunk.header.uncompressed_size, limits))
    throw McapError(where + ": claims " + std::to_string(chunk.header.uncompressed_size) +
                    " bytes uncompressed after " + std::to_string(pass->claimed) +
                    " claimed by the chunks before it, more than the reader's limit of " +
                    std::to_string(limits.max_expansion) + " x their " +
                    std::to_string(pass->chunk_records + length) + " bytes of chunk records (+ one chunk)");
  accounting.largest_chunk_buffers =
      std::max(accounting.largest_chunk_buffers, chunk.raw.size() + chunk.header.uncompressed_size);
  chunk.records = decompress(chunk.header.compression, chunk.header.records,
                             chunk.header.uncompressed_size, where, limits,
                             accounting.bytes_decompressed);
  if (chunk.header.uncompressed_crc != 0) {
    const uint32_t crc = crc32_update(0, chunk.records);
    if (crc != chunk.header.uncompressed_crc)
      throw McapError(where + ": CRC mismatch (stored " + hex32(chunk.header.uncompressed_crc) +
                      ", computed " + hex32(crc) + ")");
  }
  return chunk;
}

ChunkContents parse_chunk_records(const Buffer& records, uint64_t chunk_offset) {
  ChunkContents contents;
  const std::string where = chunk_where(chunk_offset);
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
