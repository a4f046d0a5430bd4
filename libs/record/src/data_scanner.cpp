#include "data_scanner.h"

#include <algorithm>

namespace mechsim::record::detail {
namespace {

void require_magic(const InputFile& file, uint64_t offset, const char* which) {
  if (file.size() < offset + kMagic.size() ||
      !std::ranges::equal(file.read(offset, kMagic.size()), kMagic))
    throw McapError("'" + file.path() + "' is not an MCAP file (no " + which + " magic)");
}

bool is_summary_only(uint8_t opcode) {
  return opcode == op::chunk_index || opcode == op::attachment_index ||
         opcode == op::statistics || opcode == op::metadata_index ||
         opcode == op::summary_offset || opcode == op::footer;
}

}  // namespace

DataScan scan_data_section(const InputFile& file) {
  require_magic(file, 0, "leading");
  DataScan scan;
  const uint64_t size = file.size();
  uint64_t pos = kMagic.size();
  bool first = true;
  while (true) {
    if (size - pos < kRecordPrefixSize) {
      scan.stop_reason = first        ? "file ends before the Header record"
                         : size == pos ? "file ends after a complete record"
                                       : "file ends inside a record prefix";
      break;
    }
    const Buffer prefix = file.read(pos, kRecordPrefixSize);
    ScannedRecord rec;
    rec.opcode = prefix[0];
    rec.offset = pos;
    for (int i = 0; i < 8; ++i) rec.content_length |= uint64_t(prefix[1 + i]) << (8 * i);
    if (first && rec.opcode != op::header)
      throw McapError("'" + file.path() + "': the first record is " + opcode_name(rec.opcode) +
                      ", not a Header");
    if (!first && (rec.opcode == op::header || is_summary_only(rec.opcode))) {
      scan.stop_reason = opcode_name(rec.opcode) + " record before any DataEnd";
      break;
    }
    if (rec.content_length > size - pos - kRecordPrefixSize) {
      scan.stop_reason = opcode_name(rec.opcode) + " record of " +
                         std::to_string(rec.total_length()) + " bytes is cut off by the end of file";
      break;
    }
    const uint64_t next = pos + rec.total_length();
    if (first) {
      scan.header = decode_header(file.read(rec.content_offset(), rec.content_length), pos);
      scan.header_complete = true;
      first = false;
    } else if (rec.opcode == op::data_end) {
      scan.data_section_crc = decode_data_end(file.read(rec.content_offset(), rec.content_length), pos);
      scan.data_end_found = true;
      scan.data_end_offset = pos;
      scan.stop_reason = "DataEnd";
      pos = next;
      break;
    } else {
      scan.records.push_back(rec);
    }
    pos = next;
  }
  scan.end = pos;
  return scan;
}

bool read_footer(const InputFile& file, FooterRecord& footer) {
  const uint64_t tail = kFooterRecordSize + kMagic.size();
  if (file.size() < kMagic.size() + tail) return false;
  const Buffer bytes = file.read(file.size() - tail, tail);
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.end() - kMagic.size())) return false;
  if (bytes[0] != op::footer) return false;
  uint64_t length = 0;
  for (int i = 0; i < 8; ++i) length |= uint64_t(bytes[1 + i]) << (8 * i);
  if (length != kFooterContentSize) return false;
  footer = decode_footer(std::span(bytes).subspan(kRecordPrefixSize, kFooterContentSize),
                         file.size() - tail);
  return true;
}

}  // namespace mechsim::record::detail
