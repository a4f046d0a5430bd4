#include "data_scanner.h"

#include <algorithm>

#include "crc32.h"

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

DataScan scan_data_section(const InputFile& file, const IndexedChunks& index) {
  require_magic(file, 0, "leading");
  DataScan scan;
  const uint64_t size = file.size();
  uint64_t pos = kMagic.size();
  bool first = true;
  // Records a gap at `pos` and moves to the next indexed chunk after it; false if none.
  const auto resume_after = [&](const std::string& reason) {
    const auto next = index.upper_bound(pos);
    if (next == index.end()) return false;
    scan.gaps.push_back({pos, reason + "; skipped to the indexed Chunk at offset " +
                                  std::to_string(next->first)});
    pos = next->first;
    return true;
  };
  while (true) {
    if (size - pos < kRecordPrefixSize) {
      scan.stop_reason = first        ? "file ends before the Header record"
                         : size == pos ? "file ends after a complete record"
                                       : "file ends inside a record prefix at offset " + std::to_string(pos);
      break;
    }
    const Buffer prefix = file.read(pos, kRecordPrefixSize);
    ScannedRecord rec;
    rec.opcode = prefix[0];
    rec.offset = pos;
    for (int i = 0; i < 8; ++i) rec.content_length |= uint64_t(prefix[1 + i]) << (8 * i);
    const std::string what = opcode_name(rec.opcode) + " record at offset " + std::to_string(pos);
    if (first && rec.opcode != op::header)
      throw McapError("'" + file.path() + "': the first record is " + opcode_name(rec.opcode) +
                      ", not a Header");
    if (!first && (rec.opcode == op::header || is_summary_only(rec.opcode))) {
      const std::string reason = what + " before any DataEnd";
      if (resume_after(reason)) continue;
      scan.stop_reason = reason;
      break;
    }
    if (rec.content_length > size - pos - kRecordPrefixSize) {
      const std::string reason = what + " claims " + std::to_string(rec.content_length) +
                                 " content bytes; the file ends " +
                                 std::to_string(size - pos - kRecordPrefixSize) + " bytes after its prefix";
      if (resume_after(reason)) continue;
      scan.stop_reason = reason;
      break;
    }
    if (const auto indexed = index.find(pos);
        indexed != index.end() && (rec.opcode != op::chunk || rec.total_length() != indexed->second)) {
      const std::string reason = what + " (length " + std::to_string(rec.total_length()) +
                                 ") is not the Chunk of " + std::to_string(indexed->second) +
                                 " bytes the index lists there";
      if (resume_after(reason)) continue;
      scan.stop_reason = reason;
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

IndexedChunks indexed_chunks(const InputFile& file, std::string* problem) {
  IndexedChunks chunks;
  FooterRecord footer;
  const auto fail = [&](const std::string& why) {
    chunks.clear();  // an unreadable summary offers no index to resume at
    if (problem) *problem = why;
    return chunks;
  };
  try {
    if (!read_footer(file, footer) || footer.summary_start == 0) return chunks;
    const uint64_t footer_offset = file.size() - kMagic.size() - kFooterRecordSize;
    const uint64_t summary_end = footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_offset;
    if (footer.summary_start < kMagic.size() || footer.summary_start > summary_end || summary_end > footer_offset)
      return fail("the Footer at offset " + std::to_string(footer_offset) + " points outside the file (summary at " +
                  std::to_string(footer.summary_start) + ", summary offsets at " +
                  std::to_string(footer.summary_offset_start) + ")");
    const Buffer summary = file.read(footer.summary_start, footer_offset + kFooterRecordSize - 4 - footer.summary_start);
    if (footer.summary_crc != 0 && crc32_update(0, summary) != footer.summary_crc)
      return fail("summary CRC mismatch (summary at offset " + std::to_string(footer.summary_start) + ")");
    for_each_record(std::span<const uint8_t>(summary).first(summary_end - footer.summary_start), "summary",
                    [&](uint8_t opcode, std::span<const uint8_t> content, uint64_t at) {
                      if (opcode != op::chunk_index) return;
                      const ChunkInfo c = decode_chunk_index(content, footer.summary_start + at);
                      if (c.chunk_start_offset < footer.summary_start) chunks[c.chunk_start_offset] = c.chunk_length;
                    });
  } catch (const McapError& e) {
    return fail(e.what());
  }
  return chunks;
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
