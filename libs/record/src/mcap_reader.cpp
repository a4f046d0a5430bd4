#include "mechsim/record/mcap_reader.h"

#include <algorithm>
#include <set>

#include "chunk_codec.h"
#include "crc32.h"
#include "data_scanner.h"
#include "file_io.h"
#include "records.h"

namespace mechsim::record {

using namespace detail;

namespace {

// A unit of message data in file order: a chunk, or a message stored outside chunks.
struct DataItem {
  bool is_chunk = true;
  uint64_t offset = 0;
  uint64_t length = 0;  // whole record
};

}  // namespace

struct McapReader::Impl {
  Impl(const std::string& path, ReaderOptions opts) : file(path), options(opts) {}

  void open_via_summary(const FooterRecord& footer);
  void open_via_scan();
  void add_schema(const Schema& s) {
    if (s.id != 0) schemas.emplace(s.id, s);  // id 0 is invalid per spec: ignore
  }
  void add_channel(const Channel& c) { channels.emplace(c.id, c); }

  // Messages of the chunk at `offset`, sorted by log time (stable); views into `records`.
  // `pass`: see read_chunk (nullptr for a single chunk).
  std::vector<MessageView> chunk_messages(uint64_t offset, uint64_t length, Buffer& records,
                                          PassBudget* pass) const {
    records = detail::read_chunk(file, offset, length, options.limits, accounting, pass).records;
    std::vector<MessageView> messages = parse_chunk_records(records, offset).messages;
    std::ranges::stable_sort(messages, {}, &MessageView::log_time);
    return messages;
  }
  // Strict: rethrows. Otherwise lists the damage (once per offset) and returns.
  void damage(const McapError& e, uint64_t offset) const {
    if (options.strict) throw e;
    if (damaged_offsets.insert(offset).second) damaged.push_back(e.what());
  }

  InputFile file;
  ReaderOptions options;
  FooterRecord footer;
  mutable ReadAccounting accounting;
  mutable std::vector<std::string> damaged;
  mutable std::set<uint64_t> damaged_offsets;
  bool complete = false;
  bool truncated = false;
  uint64_t scan_end = 0;
  std::string stop_reason;
  HeaderRecord header;
  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  Statistics statistics;
  std::vector<ChunkInfo> chunks;
  std::vector<SummaryOffset> summary_offsets;
  std::vector<DataItem> items;
};

void McapReader::Impl::open_via_summary(const FooterRecord& footer) {
  const uint64_t footer_offset = file.size() - kMagic.size() - kFooterRecordSize;
  const uint64_t summary_end = footer.summary_offset_start != 0 ? footer.summary_offset_start
                                                                 : footer_offset;
  if (footer.summary_start < kMagic.size() || footer.summary_start > summary_end ||
      summary_end > footer_offset)
    throw McapError("'" + file.path() + "': Footer offsets point outside the file");

  // Header: needed for profile/library; must be whole in a complete file.
  const Buffer prefix = file.read(kMagic.size(), kRecordPrefixSize);
  uint64_t header_length = 0;
  for (int i = 0; i < 8; ++i) header_length |= uint64_t(prefix[1 + i]) << (8 * i);
  if (prefix[0] != op::header || header_length > footer.summary_start)
    throw McapError("'" + file.path() + "': no Header record after the magic");
  header = decode_header(file.read(kMagic.size() + kRecordPrefixSize, header_length), kMagic.size());

  // Summary, summary offsets and footer prefix in one read, checked against summary_crc.
  const Buffer summary = file.read(footer.summary_start, footer_offset + kFooterRecordSize - 4 -
                                                             footer.summary_start);
  if (footer.summary_crc != 0 && crc32_update(0, summary) != footer.summary_crc)
    throw McapError("'" + file.path() + "': summary CRC mismatch (the summary is corrupt; "
                    "recover() rebuilds it from the data section)");

  const std::span<const uint8_t> all(summary);
  const auto section = [&](uint64_t begin, uint64_t end) {
    return all.subspan(begin - footer.summary_start, end - begin);
  };
  bool have_statistics = false;
  for_each_record(section(footer.summary_start, summary_end), "summary section of '" + file.path() + "'",
                  [&](uint8_t opcode, std::span<const uint8_t> content, uint64_t at) {
                    const uint64_t offset = footer.summary_start + at;
                    switch (opcode) {
                      case op::schema: add_schema(decode_schema(content, offset)); break;
                      case op::channel: add_channel(decode_channel(content, offset)); break;
                      case op::chunk_index: chunks.push_back(decode_chunk_index(content, offset)); break;
                      case op::statistics:
                        statistics = decode_statistics(content, offset);
                        have_statistics = true;
                        break;
                      default: break;
                    }
                  });
  if (footer.summary_offset_start != 0)
    for_each_record(section(footer.summary_offset_start, footer_offset),
                    "summary offset section of '" + file.path() + "'",
                    [&](uint8_t opcode, std::span<const uint8_t> content, uint64_t at) {
                      if (opcode == op::summary_offset)
                        summary_offsets.push_back(
                            decode_summary_offset(content, footer.summary_offset_start + at));
                    });

  // Without Statistics, or with fewer chunk indexes than chunks, the summary cannot stand
  // for the data section: read that instead (the file stays "complete").
  if (!have_statistics || chunks.size() != statistics.chunk_count) {
    schemas.clear();
    channels.clear();
    chunks.clear();
    summary_offsets.clear();
    statistics = {};
    open_via_scan();
    return;
  }
  std::ranges::sort(chunks, {}, &ChunkInfo::chunk_start_offset);
  for (const auto& c : chunks) {
    if (c.chunk_start_offset > footer.summary_start ||
        c.chunk_length > footer.summary_start - c.chunk_start_offset) {
      damage(McapError("'" + file.path() + "': the ChunkIndex of the Chunk at offset " +
                       std::to_string(c.chunk_start_offset) + " (length " + std::to_string(c.chunk_length) +
                       ") points outside the data section (summary at " +
                       std::to_string(footer.summary_start) + ")"),
             c.chunk_start_offset);
      continue;
    }
    items.push_back({true, c.chunk_start_offset, c.chunk_length});
  }
  scan_end = footer.summary_start;
  stop_reason = "read via the summary";
}

void McapReader::Impl::open_via_scan() {
  const DataScan scan = scan_data_section(file, indexed_chunks(file));
  for (const ScanGap& gap : scan.gaps) damage(McapError("'" + file.path() + "': " + gap.reason), gap.offset);
  PassBudget pass;
  header = scan.header;
  scan_end = scan.end;
  stop_reason = scan.stop_reason;
  bool have_time = false;
  auto note_time = [&](uint64_t t) {
    if (!have_time || t < statistics.message_start_time) statistics.message_start_time = t;
    if (!have_time || t > statistics.message_end_time) statistics.message_end_time = t;
    have_time = true;
  };

  for (std::size_t i = 0; i < scan.records.size(); ++i) {
    const ScannedRecord& rec = scan.records[i];
    switch (rec.opcode) {
      case op::schema:
        add_schema(decode_schema(file.read(rec.content_offset(), rec.content_length), rec.offset));
        break;
      case op::channel:
        add_channel(decode_channel(file.read(rec.content_offset(), rec.content_length), rec.offset));
        break;
      case op::message: {
        const Buffer content = file.read(rec.content_offset(), rec.content_length);
        const MessageView m = decode_message(content, rec.offset);
        ++statistics.message_count;
        ++statistics.channel_message_counts[m.channel_id];
        note_time(m.log_time);
        items.push_back({false, rec.offset, rec.total_length()});
        break;
      }
      case op::chunk: {
        OpenedChunk chunk;
        ChunkContents contents;
        try {
          chunk = detail::read_chunk(file, rec.offset, rec.total_length(), options.limits, accounting, &pass);
          contents = parse_chunk_records(chunk.records, rec.offset);
        } catch (const McapError& e) {
          damage(e, rec.offset);
          break;
        }
        const ChunkHeader& header = chunk.header;
        for (const auto& s : contents.schemas) add_schema(s);
        for (const auto& c : contents.channels) add_channel(c);
        for (const auto& m : contents.messages) {
          ++statistics.channel_message_counts[m.channel_id];
          note_time(m.log_time);
        }
        statistics.message_count += contents.messages.size();
        ChunkInfo info;
        info.message_start_time = header.message_start_time;
        info.message_end_time = header.message_end_time;
        info.chunk_start_offset = rec.offset;
        info.chunk_length = rec.total_length();
        info.compression = header.compression;
        info.compressed_size = header.records.size();
        info.uncompressed_size = header.uncompressed_size;
        // The MessageIndex records that follow the chunk, as far as they are complete.
        for (std::size_t j = i + 1; j < scan.records.size() && scan.records[j].opcode == op::message_index; ++j) {
          const Buffer idx = file.read(scan.records[j].content_offset(), 2);
          info.message_index_offsets[static_cast<uint16_t>(idx[0] | idx[1] << 8)] = scan.records[j].offset;
          info.message_index_length += scan.records[j].total_length();
        }
        chunks.push_back(std::move(info));
        items.push_back({true, rec.offset, rec.total_length()});
        break;
      }
      default: break;  // MessageIndex, Attachment, Metadata: not needed to read messages
    }
  }
  statistics.schema_count = static_cast<uint16_t>(schemas.size());
  statistics.channel_count = static_cast<uint32_t>(channels.size());
  statistics.chunk_count = static_cast<uint32_t>(chunks.size());
}

McapReader::McapReader(const std::string& path, ReaderOptions options)
    : impl_(std::make_unique<Impl>(path, options)) {
  Impl& r = *impl_;
  if (r.file.size() < kMagic.size() ||
      !std::ranges::equal(r.file.read(0, kMagic.size()), kMagic))
    throw McapError("'" + path + "' is not an MCAP file (no leading magic)");
  if (read_footer(r.file, r.footer)) {
    r.complete = true;
    if (r.footer.summary_start == 0) {
      r.open_via_scan();
      return;
    }
    try {
      r.open_via_summary(r.footer);
    } catch (const McapError& e) {
      r.damage(e, r.footer.summary_start);  // strict: rethrown
      r.schemas.clear();
      r.channels.clear();
      r.chunks.clear();
      r.summary_offsets.clear();
      r.items.clear();
      r.statistics = {};
      r.open_via_scan();
    }
  } else {
    r.truncated = true;
    r.open_via_scan();
  }
}

McapReader::~McapReader() = default;
McapReader::McapReader(McapReader&&) noexcept = default;
McapReader& McapReader::operator=(McapReader&&) noexcept = default;

const std::string& McapReader::path() const { return impl_->file.path(); }
uint64_t McapReader::file_size() const { return impl_->file.size(); }
bool McapReader::complete() const { return impl_->complete; }
bool McapReader::truncated() const { return impl_->truncated; }
uint64_t McapReader::scan_end() const { return impl_->scan_end; }
const std::string& McapReader::stop_reason() const { return impl_->stop_reason; }
const std::string& McapReader::profile() const { return impl_->header.profile; }
const std::string& McapReader::library() const { return impl_->header.library; }
const std::map<uint16_t, Schema>& McapReader::schemas() const { return impl_->schemas; }
const std::map<uint16_t, Channel>& McapReader::channels() const { return impl_->channels; }
const Statistics& McapReader::statistics() const { return impl_->statistics; }
const std::vector<ChunkInfo>& McapReader::chunks() const { return impl_->chunks; }
const std::vector<SummaryOffset>& McapReader::summary_offsets() const {
  return impl_->summary_offsets;
}
const std::vector<std::string>& McapReader::damaged() const { return impl_->damaged; }
const ReadAccounting& McapReader::accounting() const { return impl_->accounting; }

void McapReader::for_each_message(const std::function<void(const MessageView&)>& visit) const {
  PassBudget pass;
  for (const DataItem& item : impl_->items) {
    if (item.is_chunk) {
      Buffer records;
      std::vector<MessageView> messages;
      try {
        messages = impl_->chunk_messages(item.offset, item.length, records, &pass);
      } catch (const McapError& e) {
        impl_->damage(e, item.offset);  // strict: rethrown
        continue;
      }
      for (const MessageView& m : messages) visit(m);
    } else {
      const Buffer content = impl_->file.read(item.offset + kRecordPrefixSize,
                                              item.length - kRecordPrefixSize);
      visit(decode_message(content, item.offset));
    }
  }
}

namespace {
Message to_message(const MessageView& m) {
  return {m.channel_id, m.sequence, m.log_time, m.publish_time,
          std::vector<std::byte>(m.data.begin(), m.data.end())};
}
}  // namespace

std::vector<Message> McapReader::read_messages() const {
  std::vector<Message> out;
  // The Statistics count is the file's claim (unchecked when the summary CRC is 0): a hint
  // bounded by the Message records the file could hold uncompressed, never a size to allocate.
  constexpr uint64_t kMinMessageRecordSize = kRecordPrefixSize + 2 + 4 + 8 + 8;
  out.reserve(std::min(impl_->statistics.message_count, impl_->file.size() / kMinMessageRecordSize));
  for_each_message([&](const MessageView& m) { out.push_back(to_message(m)); });
  return out;
}

std::vector<Message> McapReader::read_chunk(const ChunkInfo& chunk) const {
  Buffer records;
  std::vector<Message> out;
  for (const MessageView& m : impl_->chunk_messages(chunk.chunk_start_offset, chunk.chunk_length, records, nullptr))
    out.push_back(to_message(m));
  return out;
}

namespace {

// The SummaryOffset groups must lie in the summary section and hold only records of their
// opcode, ending exactly at their stated length.
void check_summary_offsets(const InputFile& file, const FooterRecord& footer,
                           const std::vector<SummaryOffset>& groups, std::vector<std::string>& problems) {
  const uint64_t summary_end = footer.summary_offset_start;
  for (const SummaryOffset& g : groups) {
    const std::string what = "SummaryOffset for " + opcode_name(g.group_opcode) + " records (group at offset " +
                             std::to_string(g.group_start) + ", " + std::to_string(g.group_length) + " bytes)";
    if (g.group_start < footer.summary_start || g.group_start > summary_end ||
        g.group_length > summary_end - g.group_start) {
      problems.push_back(what + " points outside the summary section (" + std::to_string(footer.summary_start) +
                         ".." + std::to_string(summary_end) + ")");
      continue;
    }
    try {
      for_each_record(file.read(g.group_start, g.group_length), what,
                      [&](uint8_t opcode, std::span<const uint8_t>, uint64_t at) {
                        if (opcode != g.group_opcode)
                          throw McapError(what + ": holds a " + opcode_name(opcode) + " record at offset " +
                                          std::to_string(g.group_start + at));
                      });
    } catch (const McapError& e) {
      problems.push_back(e.what());
    }
  }
}

}  // namespace

std::vector<std::string> McapReader::verify() const {
  std::vector<std::string> problems;
  const Impl& r = *impl_;
  const InputFile& file = r.file;
  std::string summary_problem;
  const IndexedChunks index = indexed_chunks(file, &summary_problem);
  if (!summary_problem.empty()) problems.push_back(summary_problem);
  const DataScan scan = scan_data_section(file, index);
  for (const ScanGap& gap : scan.gaps) problems.push_back(gap.reason);
  if (r.complete && !scan.data_end_found)
    problems.push_back("the data section does not reach its DataEnd: " + scan.stop_reason);
  if (scan.data_end_found && scan.data_section_crc != 0) {
    uint32_t crc = 0;
    constexpr uint64_t kBlock = 1 << 20;
    for (uint64_t pos = 0; pos < scan.data_end_offset; pos += kBlock)
      crc = crc32_update(crc, file.read(pos, std::min(kBlock, scan.data_end_offset - pos)));
    if (crc != scan.data_section_crc)
      problems.push_back("data section CRC mismatch (DataEnd at offset " +
                         std::to_string(scan.data_end_offset) + ")");
  }
  if (r.complete && r.footer.summary_start != 0 && scan.data_end_found && scan.end != r.footer.summary_start)
    problems.push_back("the Footer says the summary starts at offset " + std::to_string(r.footer.summary_start) +
                       ", the data section ends at " + std::to_string(scan.end));

  // Every chunk the index or the scan names (they agree where both name one: the scan
  // checks the index), each opened on its own.
  std::map<uint64_t, uint64_t> chunks = index;
  uint64_t loose_messages = 0;
  for (const ScannedRecord& rec : scan.records) {
    if (rec.opcode == op::chunk) chunks.emplace(rec.offset, rec.total_length());
    if (rec.opcode == op::message) ++loose_messages;
  }
  uint64_t messages = loose_messages;
  bool all_chunks_sound = true;
  PassBudget pass;
  for (const auto& [offset, length] : chunks) {
    try {
      const OpenedChunk chunk = detail::read_chunk(file, offset, length, r.options.limits, r.accounting, &pass);
      messages += parse_chunk_records(chunk.records, offset).messages.size();
    } catch (const McapError& e) {
      problems.push_back(e.what());
      all_chunks_sound = false;
    }
  }
  if (r.complete && r.footer.summary_start != 0) {
    check_summary_offsets(file, r.footer, r.summary_offsets, problems);
    if (r.stop_reason == "read via the summary" && all_chunks_sound && r.statistics.message_count != messages)
      problems.push_back("the Statistics record says " + std::to_string(r.statistics.message_count) +
                         " messages, the data section holds " + std::to_string(messages));
  }
  return problems;
}

}  // namespace mechsim::record
