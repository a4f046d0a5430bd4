// A linear scan of an MCAP file's data section that reads only record prefixes (chunk
// bodies are skipped) and stops at the first record that is incomplete: how truncated
// recordings are read and recovered. With the chunk offsets of a file's index, a record
// whose length lies is skipped and the scan resumes at the next indexed chunk.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "file_io.h"
#include "records.h"

namespace mechsim::record::detail {

struct ScannedRecord {
  uint8_t opcode = 0;
  uint64_t offset = 0;          // of the opcode byte
  uint64_t content_length = 0;  // without the 9-byte prefix
  uint64_t total_length() const { return kRecordPrefixSize + content_length; }
  uint64_t content_offset() const { return offset + kRecordPrefixSize; }
};

// A stretch of the data section the scan could not read: where it starts and why.
struct ScanGap {
  uint64_t offset = 0;
  std::string reason;  // names the record, its offset and what it claimed
};

struct DataScan {
  bool header_complete = false;
  HeaderRecord header;
  std::vector<ScannedRecord> records;  // complete data-section records after the Header
  bool data_end_found = false;         // the scan ended at a DataEnd record
  uint64_t data_end_offset = 0;
  uint32_t data_section_crc = 0;
  uint64_t end = 0;                    // first byte not part of a complete record kept
  std::string stop_reason;
  std::vector<ScanGap> gaps;  // records skipped by resuming at an indexed chunk
};

// The chunks a file's index (ChunkIndex records) lists: offset -> whole record length.
// Empty unless the file ends with Footer + magic and its summary is readable and passes its
// CRC (or has none); then `problem` (if given) says why, naming the offset. Never throws.
using IndexedChunks = std::map<uint64_t, uint64_t>;
IndexedChunks indexed_chunks(const InputFile& file, std::string* problem = nullptr);

// Throws McapError if the file does not start with the magic or its first record is not
// a Header. `index` (from indexed_chunks): where a record is cut off by the end of file,
// is not allowed in a data section, or is an indexed chunk whose length field differs from
// the index, the scan records a gap and resumes at the next indexed chunk after it.
DataScan scan_data_section(const InputFile& file, const IndexedChunks& index = {});

// The Footer of a file that ends with Footer + magic, if it does.
bool read_footer(const InputFile& file, FooterRecord& footer);

}  // namespace mechsim::record::detail
