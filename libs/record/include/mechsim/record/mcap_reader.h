// An MCAP reader. A complete file (trailing magic, Footer, summary) is opened through its
// summary: schemas, channels, statistics and chunk indexes come from there and only the
// chunks are read for messages. Any other file (a recording cut short by a crash, or one
// written without a summary) is opened by a linear scan of the data section that stops
// at the first incomplete record; truncated() then tells so and scan_end() where.
//
// Messages are delivered chunk by chunk in file order, sorted by log time within a chunk
// (stable), with messages stored outside chunks in their file position. Chunk CRCs are
// checked on every read.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/record/mcap_types.h"

namespace mechsim::record {

class McapReader {
 public:
  // Throws McapError if the file cannot be opened, does not start with the MCAP magic, or
  // has a complete footer whose summary is corrupt (CRC mismatch, bad offsets): such a
  // file can still be rebuilt with recover().
  explicit McapReader(const std::string& path);
  ~McapReader();
  McapReader(McapReader&&) noexcept;
  McapReader& operator=(McapReader&&) noexcept;

  const std::string& path() const;
  uint64_t file_size() const;

  // True if the file ends with Footer + magic (read through the summary). A file that is
  // complete but has no summary is read by scan and is not truncated.
  bool complete() const;
  // True if the file ended before its Footer + magic: a recording that was not closed.
  bool truncated() const;
  // For a scanned file: the offset of the first byte that is not part of a complete
  // data-section record (the DataEnd end if the data section was complete), and why the
  // scan stopped there. For a complete file read via the summary: the summary start.
  uint64_t scan_end() const;
  const std::string& stop_reason() const;

  const std::string& profile() const;
  const std::string& library() const;
  const std::map<uint16_t, Schema>& schemas() const;
  const std::map<uint16_t, Channel>& channels() const;
  // From the summary's Statistics record for a complete file; computed from the readable
  // chunks for a scanned one.
  const Statistics& statistics() const;
  // Complete chunks in file order (from the ChunkIndex records, or from the scan).
  const std::vector<ChunkInfo>& chunks() const;
  // The summary section's groups (empty for a scanned file).
  const std::vector<SummaryOffset>& summary_offsets() const;

  // Calls `visit` for every message (see the class comment for the order). Throws
  // McapError on a chunk CRC mismatch or a chunk that does not decompress.
  void for_each_message(const std::function<void(const MessageView&)>& visit) const;
  std::vector<Message> read_messages() const;
  // The messages of one chunk of chunks(), sorted by log time (stable).
  std::vector<Message> read_chunk(const ChunkInfo& chunk) const;

  // Checks what reading does not: the data section CRC in DataEnd (when present and
  // non-zero) and every chunk's CRC. Returns one line per problem; empty means sound.
  std::vector<std::string> verify() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mechsim::record
