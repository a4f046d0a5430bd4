// A linear scan of an MCAP file's data section that reads only record prefixes (chunk
// bodies are skipped) and stops at the first record that is incomplete: how truncated
// recordings are read and recovered.
#pragma once

#include <cstdint>
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

struct DataScan {
  bool header_complete = false;
  HeaderRecord header;
  std::vector<ScannedRecord> records;  // complete data-section records after the Header
  bool data_end_found = false;         // the scan ended at a DataEnd record
  uint64_t data_end_offset = 0;
  uint32_t data_section_crc = 0;
  uint64_t end = 0;                    // first byte not part of a complete record kept
  std::string stop_reason;
};

// Throws McapError if the file does not start with the magic or its first record is not
// a Header.
DataScan scan_data_section(const InputFile& file);

// The Footer of a file that ends with Footer + magic, if it does.
bool read_footer(const InputFile& file, FooterRecord& footer);

}  // namespace mechsim::record::detail
