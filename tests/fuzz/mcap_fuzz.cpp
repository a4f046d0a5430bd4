// MCAP reader and recovery (libs/record), on arbitrary file bytes: open (summary or scan),
// read every message, verify, then recover() into a second file. McapError is the expected
// refusal. A recovered file must then open as complete and read without error: recover()
// promises a sound file (mcap_recover.h), so a refusal there is a bug as well.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_input_file.h"
#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_recover.h"
#include "mechsim/record/mcap_types.h"

using mechsim::record::McapError;
using mechsim::record::McapReader;

namespace {

void read_all(const McapReader& reader) {
  uint64_t bytes = 0;
  reader.for_each_message([&](const mechsim::record::MessageView& m) { bytes += m.data.size(); });
  if (reader.read_messages().size() != reader.statistics().message_count && reader.truncated()) std::abort();
  for (const auto& chunk : reader.chunks()) (void)reader.read_chunk(chunk);
  (void)reader.verify();
  (void)reader.statistics();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const mechsim::fuzz::ScratchFile input(".mcap");
  static const mechsim::fuzz::ScratchFile recovered(".recovered.mcap");
  input.write(data, size);
  try {
    McapReader reader(input.path());
    read_all(reader);
  } catch (const McapError&) {
  }
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
