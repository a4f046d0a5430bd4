#include "cdr_decoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "idl_schema.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::recorder {

int MessageLayout::field_index(std::string_view name) const {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name == name) return static_cast<int>(i);
  return -1;
}

namespace {

std::vector<MessageLayout> make_layouts() {
  std::vector<MessageLayout> layouts;
  for (const transport::TopicType* t : transport::all_topic_types()) layouts.push_back(layout_of(*t));
  layouts.push_back({transport::kFmuOutputsTypeName, "fmu.idl", {}, true});
  for (const char* name : {"Control", "Status"}) {
    const std::string file = std::string(name) == "Control" ? "control.idl" : "status.idl";
    layouts.push_back({"mechsim::msg::" + std::string(name), file, struct_members(idl_files().at(file), name)});
  }
  return layouts;
}

// Reads members of a plain CDR payload in order, aligning each as the encoding requires.
class CdrCursor {
 public:
  explicit CdrCursor(std::span<const std::byte> cdr) {
    if (cdr.size() < 4) throw CdrError("CDR sample of " + std::to_string(cdr.size()) + " bytes: no encapsulation header");
    const unsigned id = (std::to_integer<unsigned>(cdr[0]) << 8) | std::to_integer<unsigned>(cdr[1]);
    switch (id) {
      case 0x0000: big_endian_ = true, max_align_ = 8; break;   // CDR_BE (XCDR1)
      case 0x0001: big_endian_ = false, max_align_ = 8; break;  // CDR_LE (XCDR1)
      case 0x0006: big_endian_ = true, max_align_ = 4; break;   // CDR2_BE (XCDR2)
      case 0x0007: big_endian_ = false, max_align_ = 4; break;  // CDR2_LE (XCDR2)
      default: {
        char buf[64];
        std::snprintf(buf, sizeof buf, "unsupported CDR encapsulation 0x%04x", id);
        throw CdrError(std::string(buf) + " (a @final struct is plain CDR: 0x0000, 0x0001, 0x0006 or 0x0007)");
      }
    }
    payload_ = cdr.subspan(4);
  }

  template <class T>
  T scalar() {
    align(sizeof(T));
    need(sizeof(T));
    std::array<std::byte, sizeof(T)> b;
    std::memcpy(b.data(), payload_.data() + pos_, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) std::reverse(b.begin(), b.end());
    pos_ += sizeof(T);
    T v;
    std::memcpy(&v, b.data(), sizeof(T));
    return v;
  }

  bool boolean() {
    const auto v = scalar<std::uint8_t>();
    if (v > 1) throw CdrError("boolean byte " + std::to_string(v) + " at payload offset " + std::to_string(pos_ - 1));
    return v == 1;
  }

  std::string string() {
    const auto length = scalar<std::uint32_t>();  // NUL included
    if (length == 0) throw CdrError("string of length 0 (the NUL is missing)");
    need(length);
    const char* p = reinterpret_cast<const char*>(payload_.data() + pos_);
    if (p[length - 1] != '\0') throw CdrError("string not terminated by NUL");
    pos_ += length;
    return std::string(p, length - 1);
  }

 private:
  void align(std::size_t size) {
    const std::size_t a = std::min(size, max_align_);
    pos_ = (pos_ + a - 1) / a * a;
  }
  void need(std::size_t n) const {
    if (pos_ + n > payload_.size())
      throw CdrError("CDR sample too short: needs " + std::to_string(pos_ + n) + " payload bytes, has " +
                     std::to_string(payload_.size()));
  }
  std::span<const std::byte> payload_;
  std::size_t pos_ = 0;
  std::size_t max_align_ = 8;
  bool big_endian_ = false;
};

transport::SampleHeader read_header(CdrCursor& c) {
  transport::SampleHeader h;
  h.run_id = c.scalar<std::uint64_t>();
  h.step = c.scalar<std::uint64_t>();
  h.t = c.scalar<double>();
  return h;
}

// FmuOutputs' three sequences as they come.
struct FmuSequences {
  std::vector<double> reals;
  std::vector<std::int32_t> integers;
  std::vector<bool> booleans;
};

FmuSequences read_sequences(CdrCursor& c) {
  FmuSequences s;
  const auto count = [&](const char* what) {
    const auto n = c.scalar<std::uint32_t>();
    if (n > transport::kFmuOutputsBound)
      throw CdrError(std::string("FmuOutputs.") + what + " holds " + std::to_string(n) + " values, the IDL allows " +
                     std::to_string(transport::kFmuOutputsBound));
    return n;
  };
  for (std::uint32_t i = 0, n = count("reals"); i < n; ++i) s.reals.push_back(c.scalar<double>());
  for (std::uint32_t i = 0, n = count("integers"); i < n; ++i) s.integers.push_back(c.scalar<std::int32_t>());
  for (std::uint32_t i = 0, n = count("booleans"); i < n; ++i) s.booleans.push_back(c.boolean());
  return s;
}

const char* kind_word(CdrKind k) { return k == CdrKind::i32 ? "i32" : k == CdrKind::boolean ? "boolean" : "f64"; }

}  // namespace

MessageLayout layout_of(const transport::TopicType& type) {
  MessageLayout l{type.idl_name, type.idl_file, {}, type.layout == transport::TopicLayout::sequences};
  for (const auto& f : type.fields)
    l.fields.push_back({f.name, f.kind == transport::FieldKind::boolean ? CdrKind::boolean
                                : f.kind == transport::FieldKind::i32   ? CdrKind::i32
                                                                        : CdrKind::f64});
  return l;
}

std::string fields_text(const MessageLayout& layout) {
  std::string text;
  for (const auto& f : layout.fields) text += (text.empty() ? "" : ",") + f.name + ":" + kind_word(f.kind);
  return text;
}

MessageLayout fmu_layout_from_text(std::string_view text) {
  MessageLayout l{transport::kFmuOutputsTypeName, "fmu.idl", {}, true};
  while (!text.empty()) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    const auto colon = item.rfind(':');
    if (colon == std::string_view::npos || colon == 0)
      throw CdrError("field list '" + std::string(text) + "': expected name:kind items separated by commas");
    const std::string_view kind = item.substr(colon + 1);
    const CdrKind k = kind == "f64" ? CdrKind::f64 : kind == "i32" ? CdrKind::i32 : kind == "boolean" ? CdrKind::boolean : CdrKind::string;
    if (k == CdrKind::string) throw CdrError("field list: kind '" + std::string(kind) + "', expected f64, i32 or boolean");
    l.fields.push_back({std::string(item.substr(0, colon)), k});
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
  }
  return l;
}

std::optional<MessageLayout> channel_layout(std::string_view type_name, const std::map<std::string, std::string>& metadata) {
  const MessageLayout* known = find_layout(type_name);
  if (!known) return std::nullopt;
  if (known->sequences)
    if (auto it = metadata.find(kFieldsMetadataKey); it != metadata.end()) return fmu_layout_from_text(it->second);
  return *known;
}

MessageLayout unnamed_fmu_layout(std::span<const std::byte> cdr) {
  CdrCursor c(cdr);
  read_header(c);
  const FmuSequences s = read_sequences(c);
  MessageLayout l{transport::kFmuOutputsTypeName, "fmu.idl", {}, true};
  for (std::size_t i = 0; i < s.reals.size(); ++i) l.fields.push_back({"reals[" + std::to_string(i) + "]", CdrKind::f64});
  for (std::size_t i = 0; i < s.integers.size(); ++i) l.fields.push_back({"integers[" + std::to_string(i) + "]", CdrKind::i32});
  for (std::size_t i = 0; i < s.booleans.size(); ++i) l.fields.push_back({"booleans[" + std::to_string(i) + "]", CdrKind::boolean});
  return l;
}

const std::vector<MessageLayout>& all_layouts() {
  static const std::vector<MessageLayout> layouts = make_layouts();
  return layouts;
}

const MessageLayout* find_layout(std::string_view name) {
  for (const auto& l : all_layouts()) {
    std::string_view scoped = l.type_name;
    if (name == scoped || name == scoped.substr(scoped.rfind(':') + 1)) return &l;
  }
  return nullptr;
}

transport::SampleHeader decode_header(std::span<const std::byte> cdr) {
  CdrCursor c(cdr);
  return read_header(c);
}

DecodedSample decode_sample(std::span<const std::byte> cdr, const MessageLayout& layout) {
  CdrCursor c(cdr);
  DecodedSample s;
  s.header = read_header(c);
  s.values.reserve(layout.fields.size());
  if (layout.sequences) {
    const FmuSequences q = read_sequences(c);
    std::size_t reals = 0, integers = 0, booleans = 0;
    for (const auto& f : layout.fields) {
      if (f.kind == CdrKind::f64 && reals < q.reals.size()) s.values.emplace_back(q.reals[reals++]);
      else if (f.kind == CdrKind::i32 && integers < q.integers.size()) s.values.emplace_back(static_cast<std::int64_t>(q.integers[integers++]));
      else if (f.kind == CdrKind::boolean && booleans < q.booleans.size()) s.values.emplace_back(static_cast<bool>(q.booleans[booleans++]));
      else throw CdrError("FmuOutputs sample with fewer values than its " + std::to_string(layout.fields.size()) + " fields (" +
                          fields_text(layout) + ")");
    }
    if (reals != q.reals.size() || integers != q.integers.size() || booleans != q.booleans.size())
      throw CdrError("FmuOutputs sample with more values than its fields (" + fields_text(layout) + ")");
    return s;
  }
  for (const auto& f : layout.fields) {
    switch (f.kind) {
      case CdrKind::f64: s.values.emplace_back(c.scalar<double>()); break;
      case CdrKind::f32: s.values.emplace_back(static_cast<double>(c.scalar<float>())); break;
      case CdrKind::boolean: s.values.emplace_back(c.boolean()); break;
      case CdrKind::octet: s.values.emplace_back(static_cast<std::uint64_t>(c.scalar<std::uint8_t>())); break;
      case CdrKind::i16: s.values.emplace_back(static_cast<std::int64_t>(c.scalar<std::int16_t>())); break;
      case CdrKind::u16: s.values.emplace_back(static_cast<std::uint64_t>(c.scalar<std::uint16_t>())); break;
      case CdrKind::i32: s.values.emplace_back(static_cast<std::int64_t>(c.scalar<std::int32_t>())); break;
      case CdrKind::u32: s.values.emplace_back(static_cast<std::uint64_t>(c.scalar<std::uint32_t>())); break;
      case CdrKind::i64: s.values.emplace_back(c.scalar<std::int64_t>()); break;
      case CdrKind::u64: s.values.emplace_back(c.scalar<std::uint64_t>()); break;
      case CdrKind::string: s.values.emplace_back(c.string()); break;
    }
  }
  return s;
}

double as_number(const FieldValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* b = std::get_if<bool>(&v)) return *b ? 1.0 : 0.0;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return static_cast<double>(*u);
  return std::numeric_limits<double>::quiet_NaN();
}

std::string to_text(const FieldValue& v) {
  if (const auto* d = std::get_if<double>(&v)) {
    // The shortest text that reads back to the same double.
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, *d);
    return std::string(buf, r.ptr);
  }
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return std::to_string(*u);
  return std::get<std::string>(v);
}

}  // namespace mechsim::recorder
