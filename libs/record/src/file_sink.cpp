#include "file_sink.h"

#include <algorithm>

#include "crc32.h"

namespace mechsim::record::detail {

McapFileSink::McapFileSink(const std::string& path, const HeaderRecord& header, bool sync_chunks)
    : file_(path), sync_chunks_(sync_chunks) {
  Buffer b;
  encode_magic(b);
  encode_header(b, header);
  append_data(b);
}

void McapFileSink::append_data(std::span<const uint8_t> bytes) {
  file_.append(bytes);
  data_crc_ = crc32_update(data_crc_, bytes);
  position_ += bytes.size();
}

void McapFileSink::note_message_time(uint64_t log_time) {
  if (!have_message_time_ || log_time < stats_.message_start_time)
    stats_.message_start_time = log_time;
  if (!have_message_time_ || log_time > stats_.message_end_time) stats_.message_end_time = log_time;
  have_message_time_ = true;
}

void McapFileSink::write_schema(const Schema& schema) {
  Buffer b;
  encode_schema(b, schema);
  append_data(b);
  remember_schema(schema);
}

void McapFileSink::write_channel(const Channel& channel) {
  Buffer b;
  encode_channel(b, channel);
  append_data(b);
  remember_channel(channel);
}

void McapFileSink::write_loose_message(const MessageView& m) {
  Buffer b;
  encode_message(b, m.channel_id, m.sequence, m.log_time, m.publish_time, as_u8(m.data));
  append_data(b);
  note_message_time(m.log_time);
  ++stats_.message_count;
  ++stats_.channel_message_counts[m.channel_id];
}

void McapFileSink::write_chunk(std::span<const uint8_t> chunk_record, const ChunkHeader& header,
                               const MessageIndex& index) {
  ChunkInfo info;
  info.message_start_time = header.message_start_time;
  info.message_end_time = header.message_end_time;
  info.chunk_start_offset = position_;
  info.chunk_length = chunk_record.size();
  info.compression = header.compression;
  info.compressed_size = header.records.size();
  info.uncompressed_size = header.uncompressed_size;

  Buffer b(chunk_record.begin(), chunk_record.end());
  uint64_t chunk_messages = 0;
  for (const auto& [channel, entries] : index) {
    if (entries.empty()) continue;
    info.message_index_offsets[channel] = position_ + b.size();
    encode_message_index(b, channel, entries);
    stats_.channel_message_counts[channel] += entries.size();
    chunk_messages += entries.size();
  }
  info.message_index_length = b.size() - chunk_record.size();
  append_data(b);
  if (sync_chunks_) file_.data_sync();

  if (chunk_messages > 0) {
    note_message_time(header.message_start_time);
    note_message_time(header.message_end_time);
  }
  stats_.message_count += chunk_messages;
  chunk_indexes_.push_back(std::move(info));
}

void McapFileSink::finish() {
  if (finished_) return;
  finished_ = true;

  Buffer tail;
  encode_data_end(tail, data_crc_);
  const uint64_t summary_start = position_ + tail.size();

  // Summary groups, each a run of one opcode, with a SummaryOffset pointing at each.
  Buffer summary;
  std::vector<SummaryOffset> groups;
  auto group = [&](uint8_t opcode, auto&& encode_all) {
    const std::size_t begin = summary.size();
    encode_all();
    if (summary.size() > begin)
      groups.push_back({opcode, summary_start + begin, summary.size() - begin});
  };
  group(op::schema, [&] { for (const auto& [id, s] : schemas_) encode_schema(summary, s); });
  group(op::channel, [&] { for (const auto& [id, c] : channels_) encode_channel(summary, c); });
  stats_.schema_count = static_cast<uint16_t>(schemas_.size());
  stats_.channel_count = static_cast<uint32_t>(channels_.size());
  stats_.chunk_count = static_cast<uint32_t>(chunk_indexes_.size());
  group(op::statistics, [&] { encode_statistics(summary, stats_); });
  group(op::chunk_index, [&] { for (const auto& c : chunk_indexes_) encode_chunk_index(summary, c); });

  const uint64_t summary_offset_start = summary_start + summary.size();
  for (const auto& g : groups) encode_summary_offset(summary, g);

  FooterRecord footer{summary_start, summary_offset_start, 0};
  Buffer footer_bytes;
  encode_footer(footer_bytes, footer);
  // The summary CRC covers the summary, the SummaryOffsets and the Footer up to (not
  // including) its summary_crc field.
  uint32_t crc = crc32_update(0, summary);
  crc = crc32_update(crc, std::span(footer_bytes).first(footer_bytes.size() - 4));
  footer.summary_crc = crc;
  footer_bytes.clear();
  encode_footer(footer_bytes, footer);

  tail.insert(tail.end(), summary.begin(), summary.end());
  tail.insert(tail.end(), footer_bytes.begin(), footer_bytes.end());
  encode_magic(tail);
  file_.append(tail);
  position_ += tail.size();
  if (sync_chunks_) file_.data_sync();
  file_.close();
}

}  // namespace mechsim::record::detail
