// CRC-32 with the zlib polynomial (reflected 0xEDB88320), as MCAP uses for chunk, data
// section and summary checksums. zlib calling convention: start with 0, feed the returned
// value back in to continue over more bytes.
#pragma once

#include <cstdint>
#include <span>

namespace mechsim::record::detail {

uint32_t crc32_update(uint32_t crc, std::span<const uint8_t> bytes);

}  // namespace mechsim::record::detail
