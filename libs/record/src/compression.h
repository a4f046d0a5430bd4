// Chunk compression with the libraries MCAP names: zstd frames and LZ4 frames.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "byte_io.h"
#include "mechsim/record/mcap_types.h"

namespace mechsim::record::detail {

Buffer compress(Compression compression, std::span<const uint8_t> data);

// Decompresses a chunk's records; the result must be exactly `uncompressed_size` bytes.
// Throws McapError (naming `where`) for an unknown compression or corrupt data.
Buffer decompress(const std::string& compression, std::span<const uint8_t> data,
                  uint64_t uncompressed_size, const std::string& where);

}  // namespace mechsim::record::detail
