// The MCAP record layouts (spec: magic, then <opcode u8><content length u64><content>
// records): encoding of complete records and decoding of record contents.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "byte_io.h"
#include "mechsim/record/mcap_types.h"

namespace mechsim::record::detail {

inline constexpr std::array<uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

namespace op {
inline constexpr uint8_t header = 0x01;
inline constexpr uint8_t footer = 0x02;
inline constexpr uint8_t schema = 0x03;
inline constexpr uint8_t channel = 0x04;
inline constexpr uint8_t message = 0x05;
inline constexpr uint8_t chunk = 0x06;
inline constexpr uint8_t message_index = 0x07;
inline constexpr uint8_t chunk_index = 0x08;
inline constexpr uint8_t attachment = 0x09;
inline constexpr uint8_t attachment_index = 0x0A;
inline constexpr uint8_t statistics = 0x0B;
inline constexpr uint8_t metadata = 0x0C;
inline constexpr uint8_t metadata_index = 0x0D;
inline constexpr uint8_t summary_offset = 0x0E;
inline constexpr uint8_t data_end = 0x0F;
}  // namespace op

std::string opcode_name(uint8_t opcode);

inline constexpr uint64_t kRecordPrefixSize = 9;          // opcode + uint64 length
inline constexpr uint64_t kFooterContentSize = 8 + 8 + 4;
inline constexpr uint64_t kFooterRecordSize = kRecordPrefixSize + kFooterContentSize;

struct HeaderRecord {
  std::string profile;
  std::string library;
};

struct FooterRecord {
  uint64_t summary_start = 0;
  uint64_t summary_offset_start = 0;
  uint32_t summary_crc = 0;
};

// A Chunk record's fields; `records` views the (compressed) records inside the content.
struct ChunkHeader {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t uncompressed_size = 0;
  uint32_t uncompressed_crc = 0;
  std::string compression;
  std::span<const uint8_t> records;
};

struct MessageIndexEntry {
  uint64_t log_time;
  uint64_t offset;  // of the Message record in the uncompressed chunk records
};
using MessageIndex = std::map<uint16_t, std::vector<MessageIndexEntry>>;

// Encoders append one complete record (opcode, length, content) to `out`.
void encode_magic(Buffer& out);
void encode_header(Buffer& out, const HeaderRecord& h);
void encode_footer(Buffer& out, const FooterRecord& f);
void encode_schema(Buffer& out, const Schema& s);
void encode_channel(Buffer& out, const Channel& c);
void encode_message(Buffer& out, uint16_t channel_id, uint32_t sequence, uint64_t log_time,
                    uint64_t publish_time, std::span<const uint8_t> data);
void encode_chunk(Buffer& out, const ChunkHeader& h);  // h.records: compressed bytes
void encode_message_index(Buffer& out, uint16_t channel_id,
                          const std::vector<MessageIndexEntry>& entries);
void encode_chunk_index(Buffer& out, const ChunkInfo& c);
void encode_statistics(Buffer& out, const Statistics& s);
void encode_summary_offset(Buffer& out, const SummaryOffset& s);
void encode_data_end(Buffer& out, uint32_t data_section_crc);

// Decoders read one record's content (without opcode and length). `offset` is the file
// offset of the record, for error messages. Overruns throw McapError; extra trailing
// fields (later spec versions) are ignored.
HeaderRecord decode_header(std::span<const uint8_t> content, uint64_t offset);
FooterRecord decode_footer(std::span<const uint8_t> content, uint64_t offset);
Schema decode_schema(std::span<const uint8_t> content, uint64_t offset);
Channel decode_channel(std::span<const uint8_t> content, uint64_t offset);
MessageView decode_message(std::span<const uint8_t> content, uint64_t offset);
ChunkHeader decode_chunk(std::span<const uint8_t> content, uint64_t offset);
ChunkInfo decode_chunk_index(std::span<const uint8_t> content, uint64_t offset);
Statistics decode_statistics(std::span<const uint8_t> content, uint64_t offset);
SummaryOffset decode_summary_offset(std::span<const uint8_t> content, uint64_t offset);
uint32_t decode_data_end(std::span<const uint8_t> content, uint64_t offset);

// Calls visit(opcode, content, offset_of_record_in_buffer) for each record of a buffer
// that must hold whole records only (chunk contents, the summary section). Throws
// McapError if a record runs past the end; `where` names the buffer.
template <class Visit>
void for_each_record(std::span<const uint8_t> buffer, const std::string& where, Visit&& visit) {
  std::size_t pos = 0;
  while (pos < buffer.size()) {
    if (buffer.size() - pos < kRecordPrefixSize)
      throw McapError(where + ": truncated record header at byte " + std::to_string(pos));
    const uint8_t opcode = buffer[pos];
    uint64_t length = 0;
    for (int i = 0; i < 8; ++i) length |= uint64_t(buffer[pos + 1 + i]) << (8 * i);
    if (length > buffer.size() - pos - kRecordPrefixSize)
      throw McapError(where + ": " + opcode_name(opcode) + " record at byte " +
                      std::to_string(pos) + " runs past the end");
    visit(opcode, buffer.subspan(pos + kRecordPrefixSize, static_cast<std::size_t>(length)),
          static_cast<uint64_t>(pos));
    pos += kRecordPrefixSize + static_cast<std::size_t>(length);
  }
}

}  // namespace mechsim::record::detail
