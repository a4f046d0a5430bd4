// The file half of writing an MCAP file, shared by McapWriter (which builds chunks from
// messages) and recover() (which copies chunks): appends data-section records, keeps the
// data section CRC, the statistics and the chunk indexes, and writes the summary section,
// SummaryOffsets, Footer and trailing magic at the end.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "file_io.h"
#include "mechsim/record/mcap_types.h"
#include "records.h"

namespace mechsim::record::detail {

class McapFileSink {
 public:
  // Writes magic and Header. `sync_chunks`: fdatasync after every chunk.
  McapFileSink(const std::string& path, const HeaderRecord& header, bool sync_chunks);

  bool has_schema(uint16_t id) const { return schemas_.count(id) != 0; }
  bool has_channel(uint16_t id) const { return channels_.count(id) != 0; }

  // Writes the record to the data section (outside chunks) and keeps it for the summary.
  void write_schema(const Schema& schema);
  void write_channel(const Channel& channel);
  // Keeps a record that is already in the data section (inside a copied chunk) for the
  // summary only.
  void remember_schema(const Schema& schema) { schemas_.emplace(schema.id, schema); }
  void remember_channel(const Channel& channel) { channels_.emplace(channel.id, channel); }

  // Writes a message record outside any chunk (recovery of foreign files only).
  void write_loose_message(const MessageView& message);

  // Writes a complete Chunk record (opcode included) followed by one MessageIndex record
  // per channel of `index`, all in one write(2); then fdatasync if asked.
  void write_chunk(std::span<const uint8_t> chunk_record, const ChunkHeader& header,
                   const MessageIndex& index);

  // DataEnd, summary (Schema, Channel, Statistics, ChunkIndex groups), SummaryOffsets,
  // Footer, magic; then close. Idempotent.
  void finish();

  uint64_t position() const { return position_; }
  const Statistics& statistics() const { return stats_; }
  uint64_t chunk_count() const { return chunk_indexes_.size(); }

 private:
  void append_data(std::span<const uint8_t> bytes);  // counts towards the data section CRC
  void note_message_time(uint64_t log_time);

  OutputFile file_;
  bool sync_chunks_;
  bool finished_ = false;
  bool have_message_time_ = false;
  uint64_t position_ = 0;
  uint32_t data_crc_ = 0;
  std::map<uint16_t, Schema> schemas_;
  std::map<uint16_t, Channel> channels_;
  std::vector<ChunkInfo> chunk_indexes_;
  Statistics stats_;
};

}  // namespace mechsim::record::detail
