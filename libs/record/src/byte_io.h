// Little-endian serialization of the MCAP primitive types (uint8..uint64, String,
// length-prefixed bytes), writing into a growing buffer and reading with bounds checks.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mechsim/record/mcap_types.h"

namespace mechsim::record::detail {

using Buffer = std::vector<uint8_t>;

inline std::span<const uint8_t> as_u8(std::span<const std::byte> s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}
inline std::span<const std::byte> as_bytes(std::span<const uint8_t> s) {
  return {reinterpret_cast<const std::byte*>(s.data()), s.size()};
}

class ByteWriter {
 public:
  explicit ByteWriter(Buffer& out) : out_(out) {}
  void u8(uint8_t v) { out_.push_back(v); }
  void u16(uint16_t v) { le(v, 2); }
  void u32(uint32_t v) { le(v, 4); }
  void u64(uint64_t v) { le(v, 8); }
  void raw(std::span<const uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  void string(std::string_view s) {  // uint32 length + bytes
    u32(static_cast<uint32_t>(s.size()));
    raw({reinterpret_cast<const uint8_t*>(s.data()), s.size()});
  }
  // Overwrites 4 or 8 bytes at `at` (for length prefixes known only afterwards).
  void patch_u32(std::size_t at, uint32_t v) { patch(at, v, 4); }
  void patch_u64(std::size_t at, uint64_t v) { patch(at, v, 8); }
  std::size_t size() const { return out_.size(); }

 private:
  void le(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void patch(std::size_t at, uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_[at + i] = static_cast<uint8_t>(v >> (8 * i));
  }
  Buffer& out_;
};

// Reads fields of one record's content. Every overrun throws McapError naming `what`
// (e.g. "Channel record at offset 123").
class ByteReader {
 public:
  ByteReader(std::span<const uint8_t> data, std::string what) : d_(data), what_(std::move(what)) {}
  uint8_t u8() { return static_cast<uint8_t>(le(1)); }
  uint16_t u16() { return static_cast<uint16_t>(le(2)); }
  uint32_t u32() { return static_cast<uint32_t>(le(4)); }
  uint64_t u64() { return le(8); }
  std::span<const uint8_t> raw(uint64_t n, const char* field) {
    need(n, field);
    auto s = d_.subspan(pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return s;
  }
  std::string string(const char* field) {
    const uint32_t n = u32();
    auto s = raw(n, field);
    return {reinterpret_cast<const char*>(s.data()), s.size()};
  }
  std::span<const uint8_t> rest() {
    auto s = d_.subspan(pos_);
    pos_ = d_.size();
    return s;
  }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return d_.size() - pos_; }
  const std::string& what() const { return what_; }

 private:
  void need(uint64_t n, const char* field) const {
    if (n > d_.size() - pos_)
      throw McapError(what_ + ": field '" + field + "' needs " + std::to_string(n) +
                      " bytes, only " + std::to_string(d_.size() - pos_) + " left");
  }
  uint64_t le(int n) {
    need(static_cast<uint64_t>(n), "integer");
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= uint64_t(d_[pos_ + i]) << (8 * i);
    pos_ += static_cast<std::size_t>(n);
    return v;
  }
  std::span<const uint8_t> d_;
  std::size_t pos_ = 0;
  std::string what_;
};

}  // namespace mechsim::record::detail
