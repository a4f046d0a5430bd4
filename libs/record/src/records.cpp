#include "records.h"

namespace mechsim::record::detail {
namespace {

// Writes opcode and a length placeholder; returns where the length goes.
std::size_t begin_record(ByteWriter& w, uint8_t opcode) {
  w.u8(opcode);
  const std::size_t at = w.size();
  w.u64(0);
  return at;
}
void end_record(ByteWriter& w, std::size_t length_at) {
  w.patch_u64(length_at, w.size() - length_at - 8);
}

std::string where(uint8_t opcode, uint64_t offset) {
  return opcode_name(opcode) + " record at offset " + std::to_string(offset);
}

}  // namespace

std::string opcode_name(uint8_t opcode) {
  switch (opcode) {
    case op::header: return "Header";
    case op::footer: return "Footer";
    case op::schema: return "Schema";
    case op::channel: return "Channel";
    case op::message: return "Message";
    case op::chunk: return "Chunk";
    case op::message_index: return "MessageIndex";
    case op::chunk_index: return "ChunkIndex";
    case op::attachment: return "Attachment";
    case op::attachment_index: return "AttachmentIndex";
    case op::statistics: return "Statistics";
    case op::metadata: return "Metadata";
    case op::metadata_index: return "MetadataIndex";
    case op::summary_offset: return "SummaryOffset";
    case op::data_end: return "DataEnd";
    default: {
      static const char* hex = "0123456789ABCDEF";
      return std::string("opcode 0x") + hex[opcode >> 4] + hex[opcode & 0xF];
    }
  }
}

void encode_magic(Buffer& out) { out.insert(out.end(), kMagic.begin(), kMagic.end()); }

void encode_header(Buffer& out, const HeaderRecord& h) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::header);
  w.string(h.profile);
  w.string(h.library);
  end_record(w, at);
}

void encode_footer(Buffer& out, const FooterRecord& f) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::footer);
  w.u64(f.summary_start);
  w.u64(f.summary_offset_start);
  w.u32(f.summary_crc);
  end_record(w, at);
}

void encode_schema(Buffer& out, const Schema& s) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::schema);
  w.u16(s.id);
  w.string(s.name);
  w.string(s.encoding);
  w.string(s.data);  // uint32 length-prefixed bytes: same layout as a String
  end_record(w, at);
}

void encode_channel(Buffer& out, const Channel& c) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::channel);
  w.u16(c.id);
  w.u16(c.schema_id);
  w.string(c.topic);
  w.string(c.message_encoding);
  const std::size_t map_at = w.size();
  w.u32(0);
  for (const auto& [key, value] : c.metadata) {
    w.string(key);
    w.string(value);
  }
  w.patch_u32(map_at, static_cast<uint32_t>(w.size() - map_at - 4));
  end_record(w, at);
}

void encode_message(Buffer& out, uint16_t channel_id, uint32_t sequence, uint64_t log_time,
                    uint64_t publish_time, std::span<const uint8_t> data) {
  ByteWriter w(out);
  w.u8(op::message);
  w.u64(2 + 4 + 8 + 8 + data.size());
  w.u16(channel_id);
  w.u32(sequence);
  w.u64(log_time);
  w.u64(publish_time);
  w.raw(data);
}

void encode_chunk(Buffer& out, const ChunkHeader& h) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::chunk);
  w.u64(h.message_start_time);
  w.u64(h.message_end_time);
  w.u64(h.uncompressed_size);
  w.u32(h.uncompressed_crc);
  w.string(h.compression);
  w.u64(h.records.size());
  w.raw(h.records);
  end_record(w, at);
}

void encode_message_index(Buffer& out, uint16_t channel_id,
                          const std::vector<MessageIndexEntry>& entries) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::message_index);
  w.u16(channel_id);
  w.u32(static_cast<uint32_t>(entries.size() * 16));
  for (const auto& e : entries) {
    w.u64(e.log_time);
    w.u64(e.offset);
  }
  end_record(w, at);
}

void encode_chunk_index(Buffer& out, const ChunkInfo& c) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::chunk_index);
  w.u64(c.message_start_time);
  w.u64(c.message_end_time);
  w.u64(c.chunk_start_offset);
  w.u64(c.chunk_length);
  w.u32(static_cast<uint32_t>(c.message_index_offsets.size() * (2 + 8)));
  for (const auto& [channel, offset] : c.message_index_offsets) {
    w.u16(channel);
    w.u64(offset);
  }
  w.u64(c.message_index_length);
  w.string(c.compression);
  w.u64(c.compressed_size);
  w.u64(c.uncompressed_size);
  end_record(w, at);
}

void encode_statistics(Buffer& out, const Statistics& s) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::statistics);
  w.u64(s.message_count);
  w.u16(s.schema_count);
  w.u32(s.channel_count);
  w.u32(s.attachment_count);
  w.u32(s.metadata_count);
  w.u32(s.chunk_count);
  w.u64(s.message_start_time);
  w.u64(s.message_end_time);
  w.u32(static_cast<uint32_t>(s.channel_message_counts.size() * (2 + 8)));
  for (const auto& [channel, count] : s.channel_message_counts) {
    w.u16(channel);
    w.u64(count);
  }
  end_record(w, at);
}

void encode_summary_offset(Buffer& out, const SummaryOffset& s) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::summary_offset);
  w.u8(s.group_opcode);
  w.u64(s.group_start);
  w.u64(s.group_length);
  end_record(w, at);
}

void encode_data_end(Buffer& out, uint32_t data_section_crc) {
  ByteWriter w(out);
  const auto at = begin_record(w, op::data_end);
  w.u32(data_section_crc);
  end_record(w, at);
}

HeaderRecord decode_header(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::header, offset));
  HeaderRecord h;
  h.profile = r.string("profile");
  h.library = r.string("library");
  return h;
}

FooterRecord decode_footer(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::footer, offset));
  FooterRecord f;
  f.summary_start = r.u64();
  f.summary_offset_start = r.u64();
  f.summary_crc = r.u32();
  return f;
}

Schema decode_schema(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::schema, offset));
  Schema s;
  s.id = r.u16();
  s.name = r.string("name");
  s.encoding = r.string("encoding");
  s.data = r.string("data");
  return s;
}

Channel decode_channel(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::channel, offset));
  Channel c;
  c.id = r.u16();
  c.schema_id = r.u16();
  c.topic = r.string("topic");
  c.message_encoding = r.string("message_encoding");
  const uint32_t map_length = r.u32();
  ByteReader m(r.raw(map_length, "metadata"), r.what() + " metadata");
  while (m.remaining() > 0) {
    std::string key = m.string("metadata key");
    c.metadata[std::move(key)] = m.string("metadata value");
  }
  return c;
}

MessageView decode_message(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::message, offset));
  MessageView m;
  m.channel_id = r.u16();
  m.sequence = r.u32();
  m.log_time = r.u64();
  m.publish_time = r.u64();
  m.data = as_bytes(r.rest());
  return m;
}

ChunkHeader decode_chunk(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::chunk, offset));
  ChunkHeader h;
  h.message_start_time = r.u64();
  h.message_end_time = r.u64();
  h.uncompressed_size = r.u64();
  h.uncompressed_crc = r.u32();
  h.compression = r.string("compression");
  const uint64_t records_size = r.u64();
  h.records = r.raw(records_size, "records");
  return h;
}

ChunkInfo decode_chunk_index(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::chunk_index, offset));
  ChunkInfo c;
  c.message_start_time = r.u64();
  c.message_end_time = r.u64();
  c.chunk_start_offset = r.u64();
  c.chunk_length = r.u64();
  const uint32_t map_length = r.u32();
  ByteReader m(r.raw(map_length, "message_index_offsets"), r.what() + " message_index_offsets");
  while (m.remaining() > 0) {
    const uint16_t channel = m.u16();
    c.message_index_offsets[channel] = m.u64();
  }
  c.message_index_length = r.u64();
  c.compression = r.string("compression");
  c.compressed_size = r.u64();
  c.uncompressed_size = r.u64();
  return c;
}

Statistics decode_statistics(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::statistics, offset));
  Statistics s;
  s.message_count = r.u64();
  s.schema_count = r.u16();
  s.channel_count = r.u32();
  s.attachment_count = r.u32();
  s.metadata_count = r.u32();
  s.chunk_count = r.u32();
  s.message_start_time = r.u64();
  s.message_end_time = r.u64();
  const uint32_t map_length = r.u32();
  ByteReader m(r.raw(map_length, "channel_message_counts"), r.what() + " channel_message_counts");
  while (m.remaining() > 0) {
    const uint16_t channel = m.u16();
    s.channel_message_counts[channel] = m.u64();
  }
  return s;
}

SummaryOffset decode_summary_offset(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::summary_offset, offset));
  SummaryOffset s;
  s.group_opcode = r.u8();
  s.group_start = r.u64();
  s.group_length = r.u64();
  return s;
}

uint32_t decode_data_end(std::span<const uint8_t> content, uint64_t offset) {
  ByteReader r(content, where(op::data_end, offset));
  return r.u32();
}

}  // namespace mechsim::record::detail
