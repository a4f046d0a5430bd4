// An FMU's serialized state inside a block's saved discrete state (models::Block::
// save_discrete_state, a vector of doubles that checkpoints store): the byte count, then
// the bytes four to a double, each double an exact integer below 2^32. So the bytes come
// back whole whatever carries the doubles (no NaN payloads, nothing a finiteness check or
// a text format could spoil).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace mechsim::fmi {

void append_bytes(std::vector<double>& out, std::span<const std::uint8_t> bytes);
// Reads what append_bytes wrote at the front of `in`; returns false when `in` does not
// hold such a record (then `bytes` is left empty). `used` is the number of doubles read.
bool read_bytes(std::span<const double> in, std::vector<std::uint8_t>& bytes, std::size_t& used);

}  // namespace mechsim::fmi
