// What a recording holds (`mechsim bag info`) and its samples as CSV (`mechsim bag
// export`), decoded with cdr_decoder.h. Works on complete and on truncated files (a
// truncated file is read up to its last complete chunk).
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mechsim/record/mcap_types.h"

namespace mechsim::recorder {

// How `bag info` and `bag export` read a file that may be damaged or hostile.
struct BagReadOptions {
  // false (the default): a damaged chunk is skipped and listed, the sound chunks are read.
  // true: any problem refuses the file (record::McapError naming it and its offset).
  bool strict = false;
  record::ChunkLimits limits;  // what one chunk may claim (docs/recording.md)
};

struct BagTopic {
  std::string topic;
  std::string type;              // schema name ("" without a schema)
  std::string message_encoding;  // "cdr"
  std::map<std::string, std::string> metadata;
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;       // message payloads (CDR), uncompressed
  std::uint64_t publish_first_ns = 0, publish_last_ns = 0;  // simulated time
  std::uint64_t log_first_ns = 0, log_last_ns = 0;          // wall time received
  std::vector<std::uint64_t> run_ids;  // distinct, in order of first appearance
  // Data topics (one sample per step): per run, steps between the first and the last that
  // are absent, and steps seen more than once. Zero for control and status.
  std::uint64_t step_first = 0, step_last = 0;
  std::uint64_t missing_steps = 0;
  std::uint64_t duplicate_steps = 0;
  std::uint64_t undecodable = 0;  // messages the decoder refused (unknown type, bad bytes)
};

struct BagInfo {
  std::string path;
  std::uint64_t file_size = 0;
  bool complete = false;   // Footer + magic present and nothing wrong (no problems)
  bool damaged = false;    // verify() found problems; the sound chunks were read
  bool truncated = false;  // ended before its Footer: a recording that was not closed
  std::string stop_reason; // for a truncated file: where and why reading stopped
  std::uint64_t readable_bytes = 0;  // up to the end of the last complete record
  std::vector<std::string> compressions;  // of the chunks ("none" for uncompressed ones)
  std::uint64_t chunks = 0;
  std::uint64_t compressed_bytes = 0, uncompressed_bytes = 0;  // chunk records
  std::uint64_t messages = 0;
  std::uint64_t log_start_ns = 0, log_end_ns = 0;
  std::uint64_t publish_start_ns = 0, publish_end_ns = 0;
  std::vector<BagTopic> topics;          // sorted by topic name
  std::vector<std::string> problems;     // McapReader::verify(), each naming its offset
  std::uint64_t chunks_skipped = 0;      // damaged chunks whose messages are not counted
  record::ReadAccounting accounting;     // the reader's decompression accounting
};

// Throws record::McapError for a file that is not MCAP (or unreadable), and with
// options.strict for a file with any problem.
BagInfo inspect_bag(const std::string& path, const BagReadOptions& options = {});
nlohmann::json to_json(const BagInfo& info);
// `mechsim bag info`'s exit code for a file it could read: 0 sound, 3 read with problems
// (listed). A refusal (record::McapError) is 1.
inline constexpr int kBagDamagedExitCode = 3;
int exit_code(const BagInfo& info);
// The human-readable summary `mechsim bag info` prints.
std::string format_bag_info(const BagInfo& info);

struct ExportedTopic {
  std::string topic;
  std::string file;
  std::uint64_t rows = 0;
  std::uint64_t skipped = 0;  // messages that could not be decoded
};

// "cam/state" -> "cam_state.csv" (every character other than letters, digits, '-', '.'
// and '_' becomes '_').
std::string csv_file_name(const std::string& topic);

// One CSV per topic in `dir` (created): columns t, step, run_id and the IDL field names,
// one row per message in recording order. Doubles are written in the shortest form that
// reads back bit-exact, booleans as 0/1, strings quoted (RFC 4180). Topics of a type the
// decoder does not know are skipped (returned with file ""). Throws std::runtime_error
// when a file cannot be written. A damaged chunk is skipped and listed in `skipped_chunks`
// (with options.strict: record::McapError instead).
struct BagExport {
  std::vector<ExportedTopic> topics;
  std::vector<std::string> skipped_chunks;  // why each, naming its offset
};
BagExport export_csv(const std::string& bag, const std::string& dir, const BagReadOptions& options = {});
// `mechsim bag export`'s exit code for a file it exported: 0, or 3 when chunks were skipped.
int exit_code(const BagExport& result);

}  // namespace mechsim::recorder
