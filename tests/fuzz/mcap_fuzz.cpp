// MCAP reader and recovery (libs/record) and what `mechsim bag info` / `bag export` run on
// them (tools/record/bag_inspect), on arbitrary file bytes: open (summary or scan), read
// every message, verify, strict and lenient; inspect and export to CSV; then recover() into
// a second file. McapError is the expected refusal. A recovered file must then open as
// complete and read without error: recover() promises a sound file (mcap_recover.h), so a
// refusal there is a bug as well. Whatever a chunk claims, the reader's own accounting must
// stay within the budget of one chunk (docs/recording.md "Reading files from elsewhere").
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "bag_inspect.h"
#include "fuzz_input_file.h"
#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_types.h"

using mechsim::record::McapError;
using mechsim::record::McapReader;

namespace {

// One chunk's record plus its uncompressed buffer: the reader's stated per-chunk budget.
void check_budget(const McapReader& reader) {
  const mechsim::record::ChunkLimits limits;
  const uint64_t budget = 2 * limits.max_chunk_size + limits.max_chunk_size / 64 + 4096;
  if (reader.accounting().largest_chunk_buffers > budget) std::abort();
  // The decoders stop one byte past a chunk's claim: never more than the claims allow.
  if (reader.accounting().bytes_decompressed > reader.accounting().chunks_opened * (limits.max_chunk_size + 1))
    std::abort();
}

void read_all(const McapReader& reader) {
  uint64_t bytes = 0;
  reader.for_each_message([&](const mechsim::record::MessageView& m) { bytes += m.data.size(); });
  if (reader.read_messages().size() != reader.statistics().message_count && reader.truncated() &&
      reader.damaged().empty())
    std::abort();
  for (const auto& chunk : reader.chunks()) {
    try {
      (void)reader.read_chunk(chunk);  // throws for a damaged chunk, lenient or not
    } catch (const McapError&) {
    }
  }
  (void)reader.verify();
  (void)reader.statistics();
  check_budget(reader);
}

void inspect_and_export(const std::string& path, const std::string& csv_dir) {
  try {
    (void)mechsim::recorder::inspect_bag(path);
    (void)mechsim::recorder::export_csv(path, csv_dir);
  } catch (const McapError&) {
  } catch (const std::runtime_error& e) {
    // A topic name too long for a file name is the file system's refusal, not a bug.
    if (std::string(e.what()).rfind("cannot write", 0) != 0) throw;
  }
  std::error_code ec;
  std::filesystem::remove_all(csv_dir, ec);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const mechsim::fuzz::ScratchFile input(".mcap");
  static const mechsim::fuzz::ScratchFile recovered(".recovered.mcap");
  static const mechsim::fuzz::ScratchFile csv(".csv");
  input.write(data, size);
  try {
    McapReader reader(input.path());
    read_all(reader);
  } catch (const McapError&) {
  }
  try {
    mechsim::record::ReaderOptions lenient;
    lenient.strict = false;
    McapReader reader(input.path(), lenient);
    read_all(reader);
  } catch (const McapError&) {  // not MCAP at all
  }
  inspect_and_export(input.path(), csv.path());
  bool was_recovered = false;
  try {
    mechsim::record::recover(input.path(), recovered.path());
    was_recovered = true;
  } catch (const McapError&) {
  }
  if (was_recovered) {
    McapReader reader(recovered.path());  // throws (and so fails the run) if unsound
    if (!reader.complete() || !reader.verify().empty()) std::abort();
    read_all(reader);
  }
  return 0;
}
