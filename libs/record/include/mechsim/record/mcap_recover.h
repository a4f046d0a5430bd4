// Rebuilding a complete MCAP file (with summary and index) from a recording that was cut
// short, e.g. by a crash of the recorder.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mechsim/record/mcap_types.h"

namespace mechsim::record {

struct RecoveryReport {
  bool input_complete = false;  // the input already had Footer + magic
  uint64_t input_size = 0;
  uint64_t scan_end = 0;         // first byte of the input that was not kept
  std::string stop_reason;       // why the scan of the input stopped there
  uint64_t schemas = 0;          // records kept
  uint64_t channels = 0;
  uint64_t chunks = 0;
  uint64_t messages = 0;         // in kept chunks and outside chunks
  uint64_t chunks_dropped = 0;   // complete chunks that failed their CRC, limits or decompression
  // Why each dropped chunk and each skipped stretch was not kept, naming the offset.
  std::vector<std::string> dropped;
};

// Copies every complete record of `in`'s data section to `out` (complete chunks byte for
// byte, with fresh MessageIndex records; Schema, Channel and Message records outside chunks
// as they are), then writes DataEnd, summary, SummaryOffsets, Footer and magic. Works on
// complete inputs too (it rebuilds their summary). Throws McapError if `in` does not start
// with the MCAP magic, std::runtime_error if `out` cannot be written. `in` and `out` must
// differ. A chunk over `limits` or otherwise damaged is dropped (listed in `dropped`); when
// `in` has a sound index, a record whose length lies is stepped over and every sound chunk
// after it is kept.
RecoveryReport recover(const std::string& in, const std::string& out, const ChunkLimits& limits = {});

}  // namespace mechsim::record
