// The CDR decoder of recorded samples (tools/record/cdr_decoder.cpp), as `mechsim bag
// export` and `topic echo` run it. Input: one byte choosing the layout (every mechsim type,
// all_layouts()), then the sample bytes (encapsulation header + payload). CdrError is the
// expected refusal; a decoded sample has one value per field, each printable.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "cdr_decoder.h"

using namespace mechsim::recorder;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const auto& layouts = all_layouts();
  const MessageLayout& layout = layouts[data[0] % layouts.size()];
  const std::span<const std::byte> cdr(reinterpret_cast<const std::byte*>(data + 1), size - 1);
  try {
    (void)decode_header(cdr);
    const DecodedSample s = decode_sample(cdr, layout);
    if (s.values.size() != layout.fields.size()) std::abort();
    for (const auto& v : s.values) {
      (void)as_number(v);
      if (to_text(v).empty() && !std::holds_alternative<std::string>(v)) std::abort();
    }
  } catch (const CdrError&) {
  }
  return 0;
}
