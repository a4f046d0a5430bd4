// An MCAP reader. A complete file (trailing magic, Footer, summary) is opened through its
// summary: schemas, channels, statistics and chunk indexes come from there and only the
// chunks are read for messages. Any other file (a recording cut short by a crash, or one
// written without a summary) is opened by a linear scan of the data section that stops
// at the first incomplete record; truncated() then tells so and scan_end() where.
//
// Messages are delivered chunk by chunk in file order, sorted by log time within a chunk
// (stable), with messages stored outside chunks in their file position. Chunk CRCs are
// checked on every read.
//
// Files from elsewhere: every chunk is bounded by ReaderOptions::limits before anything is
// read or allocated (the claim, the record, the expansion ratio), and decompression writes
// into a buffer of exactly the claimed size, so one chunk costs at most about twice
// limits.max_chunk_size however the file lies. A damaged chunk throws McapError naming its
// offset (strict, the default) or is skipped and listed in damaged() (strict = false).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mechsim/record/mcap_types.h"

namespace mechsim::record {

struct ReaderOptions {
  ChunkLimits limits;
  // true: a damaged chunk (or summary) throws McapError. false: it is skipped, listed in
  // damaged(), and the sound chunks are read (a corrupt summary is replaced by a scan).
  bool strict = true;
};

class McapReader {
 public:
  // Throws McapError if the file cannot be opened, does not start with the MCAP magic, or
  // has a complete footer whose summary is corrupt (CRC mismatch, bad offsets): such a
  // file can still be rebuilt with recover().
  explicit McapReader(const std::string& path, ReaderOptions options = {});
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

  // Checks what the file states against what it holds: every record length against the
  // file size and the ChunkIndex records, every chunk (limits, decompression, CRC), the
  // data section CRC in DataEnd (when non-zero), the Footer's and SummaryOffsets' offsets
  // and the Statistics message count. Returns one line per problem, each naming its
  // offset; empty means sound.
  std::vector<std::string> verify() const;

  // Damage met so far while reading with strict = false (chunks skipped, a summary
  // replaced by a scan), one line each naming the offset, in the order met.
  const std::vector<std::string>& damaged() const;
  // The reader's accounting of chunk decompression so far (verify() included).
  const ReadAccounting& accounting() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mechsim::record
