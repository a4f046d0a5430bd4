// Chunk compression with the libraries MCAP names: zstd frames and LZ4 frames.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "byte_io.h"
#include "mechsim/record/mcap_types.h"

namespace mechsim::record::detail {

Buffer compress(Compression compression, std::span<const uint8_t> data);

// Throws McapError (naming `where` and the claim) if a chunk of `compressed` bytes claiming
// `claimed` uncompressed bytes is over `limits`: checked before anything is allocated.
void check_claim(const std::string& compression, std::size_t compressed, uint64_t claimed,
                 const ChunkLimits& limits, const std::string& where);

// Decompresses a chunk's records into a buffer of exactly `uncompressed_size` bytes (after
// check_claim); decoding stops as soon as the data would exceed it. Adds the bytes the
// decoder produced to `produced`. Throws McapError (naming `where`) for an unknown
// compression, corrupt data or a size that differs from the claim.
Buffer decompress(const std::string& compression, std::span<const uint8_t> data,
                  uint64_t uncompressed_size, const std::string& where, const ChunkLimits& limits,
                  uint64_t& produced);

}  // namespace mechsim::record::detail
