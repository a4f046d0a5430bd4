#include "mechsim/record/mcap_recover.h"

#include <filesystem>
#include <stdexcept>

#include "chunk_codec.h"
#include "data_scanner.h"
#include "file_sink.h"
#include "records.h"

namespace mechsim::record {

using namespace detail;

namespace {

// What reading the input's chunks has spent, and what the output's chunks spend: a reader
// of the output admits its chunks against the second.
struct ChunkBudgets {
  ReadAccounting accounting;
  PassBudget pass;
  PassBudget kept;
};

// The report's account of the input before any record is copied.
RecoveryReport input_report(const InputFile& file, const DataScan& scan) {
  RecoveryReport report;
  FooterRecord footer;
  report.input_complete = read_footer(file, footer);
  report.input_size = file.size();
  report.scan_end = scan.end;
  report.stop_reason = scan.stop_reason;
  for (const ScanGap& gap : scan.gaps) report.dropped.push_back(gap.reason);
  return report;
}

// A Schema, Channel or Message record outside chunks, as it is (a schema or channel once).
void copy_loose_record(const InputFile& file, const ScannedRecord& rec, McapFileSink& sink, RecoveryReport& report) {
  const Buffer content = file.read(rec.content_offset(), rec.content_length);
  if (rec.opcode == op::schema) {
    const Schema s = decode_schema(content, rec.offset);
    if (s.id != 0 && !sink.has_schema(s.id)) {
      sink.write_schema(s);
      ++report.schemas;
    }
  } else if (rec.opcode == op::channel) {
    const Channel c = decode_channel(content, rec.offset);
    if (!sink.has_channel(c.id)) {
      sink.write_channel(c);
      ++report.channels;
    }
  } else {
    sink.write_loose_message(decode_message(content, rec.offset));
    ++report.messages;
  }
}

// A sound chunk byte for byte, with its schemas and channels remembered for the summary and
// a fresh MessageIndex.
void keep_chunk(const OpenedChunk& chunk, const ChunkContents& contents, McapFileSink& sink, RecoveryReport& report) {
  for (const auto& s : contents.schemas)
    if (s.id != 0 && !sink.has_schema(s.id)) {
      sink.remember_schema(s);
      ++report.schemas;
    }
  for (const auto& c : contents.channels)
    if (!sink.has_channel(c.id)) {
      sink.remember_channel(c);
      ++report.channels;
    }
  MessageIndex index;
  for (std::size_t k = 0; k < contents.messages.size(); ++k)
    index[contents.messages[k].channel_id].push_back({contents.messages[k].log_time, contents.message_offsets[k]});
  sink.write_chunk(chunk.raw, chunk.header, index);  // byte for byte
  ++report.chunks;
  report.messages += contents.messages.size();
}

// A Chunk record: kept when it opens, parses and fits the output's budget; else dropped,
// saying why.
void copy_chunk(const InputFile& file, const ScannedRecord& rec, const ChunkLimits& limits, ChunkBudgets& budgets,
                McapFileSink& sink, RecoveryReport& report) {
  OpenedChunk chunk;
  ChunkContents contents;
  try {
    chunk = read_chunk(file, rec.offset, rec.total_length(), limits, budgets.accounting, &budgets.pass);
    contents = parse_chunk_records(chunk.records, rec.offset);
  } catch (const McapError& e) {
    ++report.chunks_dropped;  // a complete chunk that is damaged: its data is lost
    report.dropped.push_back(e.what());
    return;
  }
  // Without the chunks dropped before it, the output must still admit this one.
  if (!admit(budgets.kept, rec.total_length(), chunk.header.uncompressed_size, limits)) {
    ++report.chunks_dropped;
    report.dropped.push_back(chunk_where(rec.offset) + ": its claim of " + std::to_string(chunk.header.uncompressed_size) +
                             " bytes exceeds the expansion budget of the chunks kept before it");
    return;
  }
  keep_chunk(chunk, contents, sink, report);
}

}  // namespace

RecoveryReport recover(const std::string& in, const std::string& out, const ChunkLimits& limits) {
  std::error_code ec;
  if (std::filesystem::equivalent(in, out, ec))
    throw std::invalid_argument("recover: input and output are the same file '" + in + "'");

  const InputFile file(in);
  // The input's index, when it has a sound one, lets the scan step over a record whose
  // length lies and keep the chunks after it.
  const DataScan scan = scan_data_section(file, indexed_chunks(file));  // throws without magic
  RecoveryReport report = input_report(file, scan);
  const HeaderRecord header = scan.header_complete ? scan.header : HeaderRecord{"", "mechsim"};
  McapFileSink sink(out, header, /*sync_chunks=*/false);
  ChunkBudgets budgets;
  for (const ScannedRecord& rec : scan.records) {
    switch (rec.opcode) {
      case op::schema:
      case op::channel:
      case op::message: copy_loose_record(file, rec, sink, report); break;
      case op::chunk: copy_chunk(file, rec, limits, budgets, sink, report); break;
      default: break;  // MessageIndex is rebuilt; Attachment/Metadata are not carried over
    }
  }
  sink.finish();
  return report;
}

}  // namespace mechsim::record
