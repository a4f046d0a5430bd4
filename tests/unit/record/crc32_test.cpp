// The CRC-32 routine must be the zlib one, or MCAP readers elsewhere reject our chunks.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "crc32.h"

namespace mechsim::record::detail {
namespace {

std::span<const uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

TEST(Crc32, StandardCheckValue) {
  // "123456789" -> 0xCBF43926 is the published check value of CRC-32/ISO-HDLC (zlib's).
  EXPECT_EQ(crc32_update(0, bytes_of("123456789")), 0xCBF43926u);
  EXPECT_EQ(crc32_update(0, {}), 0u);
}

TEST(Crc32, IncrementalEqualsWholeAtEverySplit) {
  // The 8-byte fast path and the byte tail must agree wherever a buffer is split, since
  // the writer feeds the data-section CRC record by record.
  std::string text;
  for (int i = 0; i < 100; ++i) text += static_cast<char>((i * 37 + 11) & 0xFF);
  const uint32_t whole = crc32_update(0, bytes_of(text));
  for (std::size_t split = 0; split <= text.size(); ++split) {
    const uint32_t first = crc32_update(0, bytes_of(text.substr(0, split)));
    EXPECT_EQ(crc32_update(first, bytes_of(text.substr(split))), whole) << "split " << split;
  }
}

TEST(Crc32, DetectsSingleBitFlip) {
  std::string text(1000, 'x');
  const uint32_t clean = crc32_update(0, bytes_of(text));
  text[517] ^= 0x10;
  EXPECT_NE(crc32_update(0, bytes_of(text)), clean);
}

}  // namespace
}  // namespace mechsim::record::detail
