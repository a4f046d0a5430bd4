#include "saved_state.h"

#include <cmath>

namespace mechsim::fmi {

void append_bytes(std::vector<double>& out, std::span<const std::uint8_t> bytes) {
  out.push_back(static_cast<double>(bytes.size()));
  for (std::size_t i = 0; i < bytes.size(); i += 4) {
    std::uint32_t word = 0;
    for (std::size_t j = 0; j < 4 && i + j < bytes.size(); ++j) word |= std::uint32_t{bytes[i + j]} << (8 * j);
    out.push_back(static_cast<double>(word));
  }
}

bool read_bytes(std::span<const double> in, std::vector<std::uint8_t>& bytes, std::size_t& used) {
  bytes.clear();
  used = 0;
  if (in.empty() || !(in[0] >= 0) || in[0] != std::floor(in[0])) return false;
  const auto n = static_cast<std::size_t>(in[0]);
  const std::size_t words = (n + 3) / 4;
  if (in.size() - 1 < words) return false;
  bytes.resize(n);
  for (std::size_t w = 0; w < words; ++w) {
    const double v = in[1 + w];
    if (!(v >= 0 && v <= 4294967295.0) || v != std::floor(v)) {
      bytes.clear();
      return false;
    }
    const auto word = static_cast<std::uint32_t>(v);
    for (std::size_t j = 0; j < 4 && 4 * w + j < n; ++j) bytes[4 * w + j] = static_cast<std::uint8_t>(word >> (8 * j));
  }
  used = 1 + words;
  return true;
}

}  // namespace mechsim::fmi
