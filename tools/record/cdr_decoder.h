// Decoding mechsim samples from their CDR bytes (what a recording stores), without DDS.
//
// Every mechsim type is a @final struct: Header {uint64 run_id; uint64 step; double t}
// followed by scalar members (and, in Status, bounded strings). Its plain CDR encoding is
// the 4-byte encapsulation header (representation id, options) and then the members in
// order, each aligned to its size relative to the start of the payload (the byte after the
// encapsulation header): XCDR1 aligns 8-byte members to 8, XCDR2 to 4. Booleans and octets
// take one byte, short 2, long and float 4, long long and double 8, a string a uint32
// length (NUL included), its bytes and the NUL. @final structs have no member headers in
// either version.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mechsim/transport/messages.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::recorder {

enum class CdrKind { f64, f32, boolean, octet, i16, u16, i32, u32, i64, u64, string };

struct CdrField {
  std::string name;
  CdrKind kind;
};

// The members after the header, in IDL order, and where the IDL text lives.
struct MessageLayout {
  std::string type_name;  // fully scoped, e.g. "mechsim::msg::CamState"
  std::string idl_file;   // under idl/, e.g. "cam.idl"
  std::vector<CdrField> fields;
  int field_index(std::string_view name) const;  // -1 when absent
  // FmuOutputs (idl/fmu.idl): the fields (f64, i32, boolean) travel in its three sequences,
  // each kind in field order. The generic layout find_layout gives has no fields: the
  // names are an FMU participant's (layout_of its topic type, a channel's "mechsim.fields"
  // metadata, or unnamed_fmu_layout).
  bool sequences = false;
};

// The layout of a topic type as the nodes publish it (an FMU participant's with its names).
MessageLayout layout_of(const transport::TopicType& type);
// The MCAP channel metadata key under which the recorder writes an FmuOutputs topic's field
// names and kinds ("y:f64,impacts:i32,faulted:boolean"), and the two directions.
inline constexpr const char* kFieldsMetadataKey = "mechsim.fields";
std::string fields_text(const MessageLayout& layout);
// Throws CdrError for text that is not such a list.
MessageLayout fmu_layout_from_text(std::string_view text);
// The layout of a recorded channel: by its schema's type name, and for FmuOutputs with the
// names of the channel's "mechsim.fields" metadata when it has them (else no fields: see
// unnamed_fmu_layout). nullopt for a type mechsim does not know. Throws CdrError for bad
// metadata.
std::optional<MessageLayout> channel_layout(std::string_view type_name, const std::map<std::string, std::string>& metadata);
// An FmuOutputs sample's layout where the names are not known: reals[0], ..., integers[0],
// ..., booleans[0], ... as many as the sample carries. Throws CdrError.
MessageLayout unnamed_fmu_layout(std::span<const std::byte> cdr);

// The layouts of every type mechsim publishes: the data types built from the field lists
// of transport/topic_types.h (f64 -> double, boolean -> boolean); Control and Status,
// which have no such list, parsed from the IDL text compiled in (idl_schema.h), so that a
// member added to idl/control.idl or idl/status.idl is decoded without a change here.
const std::vector<MessageLayout>& all_layouts();
// By fully scoped or short name; nullptr when unknown.
const MessageLayout* find_layout(std::string_view type_name);

using FieldValue = std::variant<double, bool, std::int64_t, std::uint64_t, std::string>;

struct DecodedSample {
  transport::SampleHeader header;
  std::vector<FieldValue> values;  // one per layout field
};

// A buffer that is not a sample of the expected layout: too short, an encapsulation other
// than plain CDR (XCDR1/XCDR2, either byte order), a string without its NUL.
class CdrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws CdrError.
DecodedSample decode_sample(std::span<const std::byte> cdr, const MessageLayout& layout);
transport::SampleHeader decode_header(std::span<const std::byte> cdr);

// A value as a number (booleans 0/1, integers converted; NaN for a string).
double as_number(const FieldValue& value);
// A value as text: doubles in the shortest form that reads back bit-exact, booleans true/false,
// integers in decimal, strings as they are.
std::string to_text(const FieldValue& value);

}  // namespace mechsim::recorder
