// The data topic types of idl/*.idl as seen by node logic: a header plus a flat list of
// scalar fields, each carried as a double on the block side (booleans as 0/1). The field
// lists here mirror the IDL in order; tests/unit/transport checks them against the .idl
// files so the two cannot drift apart. The one exception is FmuOutputs (idl/fmu.idl): its
// fields are a participant's FMU output variables, so each FMU participant has a topic type
// of its own, made by fmu_topic_type, that travels as that one IDL type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace mechsim::transport {

enum class FieldKind { f64, boolean, i32 };  // i32: FMU Integer/Int32 outputs only

struct FieldInfo {
  std::string name;
  FieldKind kind;
  // Physical bounds (SI): a received value outside them, or not finite, is refused by the
  // node that uses the field (docs/dds.md, 'Plausible samples'; the table there is checked
  // against these by tests/unit/transport). Unbounded where nothing physical limits it.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  std::string unit{};  // for messages and the docs
};

// How the fields travel. members: one IDL member per field (cam.idl, ...). sequences: the
// f64 fields in order in FmuOutputs.reals, the i32 ones in .integers, the booleans in
// .booleans (idl/fmu.idl).
enum class TopicLayout { members, sequences };

struct TopicType {
  std::string idl_name;   // fully scoped IDL name, e.g. "mechsim::msg::CamState"
  std::string idl_file;   // file under idl/, e.g. "cam.idl"
  std::vector<FieldInfo> fields;
  TopicLayout layout = TopicLayout::members;
  int field_index(std::string_view name) const;  // -1 when absent
  // Two topic types a writer and a reader can share a topic with: the same IDL type and
  // the same fields (FMU topic types are made per participant and per process).
  bool same_as(const TopicType& other) const;
};

// FmuOutputs (idl/fmu.idl) carries at most this many values of each kind.
inline constexpr std::size_t kFmuOutputsBound = 256;
inline constexpr const char* kFmuOutputsTypeName = "mechsim::msg::FmuOutputs";
// The topic type of one FMU participant: its output variables as fields (layout
// sequences). Throws std::invalid_argument past kFmuOutputsBound values of one kind.
TopicType fmu_topic_type(std::vector<FieldInfo> fields);
// Where a field's value sits in its sequence: (kind, index within that kind's sequence).
std::vector<std::size_t> sequence_positions(const TopicType& type);

// The values of a sample of a sequences-layout type into FmuOutputs' three sequences, and
// back, for every backend's own sequence storage (anything indexable; the sequences sized
// by the caller when packing). `at`: sequence_positions(type).
template <class Reals, class Integers, class Booleans>
void pack_sequences(const TopicType& type, const std::vector<std::size_t>& at, const double* values, Reals& reals,
                    Integers& integers, Booleans& booleans) {
  for (std::size_t i = 0; i < type.fields.size(); ++i) {
    const FieldKind kind = type.fields[i].kind;
    if (kind == FieldKind::f64) reals[at[i]] = values[i];
    else if (kind == FieldKind::i32) integers[at[i]] = static_cast<std::int32_t>(values[i]);
    else booleans[at[i]] = values[i] != 0.0;
  }
}
// A sample shorter than the type (another FMU on the topic) leaves NaN, which the sample
// gate refuses as implausible.
template <class Reals, class Integers, class Booleans>
void unpack_sequences(const TopicType& type, const std::vector<std::size_t>& at, const Reals& reals, std::size_t n_reals,
                      const Integers& integers, std::size_t n_integers, const Booleans& booleans, std::size_t n_booleans,
                      std::vector<double>& values) {
  values.assign(type.fields.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const FieldKind kind = type.fields[i].kind;
    const std::size_t j = at[i];
    if (kind == FieldKind::f64 && j < n_reals) values[i] = reals[j];
    else if (kind == FieldKind::i32 && j < n_integers) values[i] = integers[j];
    else if (kind == FieldKind::boolean && j < n_booleans) values[i] = booleans[j] ? 1.0 : 0.0;
  }
}

// The values as a reader gets them back after the wire: booleans as 0/1, i32 fields
// truncated to int32, f64 unchanged (the in-process paths deliver exactly what DDS would).
void as_on_the_wire(const TopicType& type, std::vector<double>& values);

// All data topic types, and lookup by the short name used in code ("CamState").
const std::vector<const TopicType*>& all_topic_types();
const TopicType* find_topic_type(std::string_view short_or_scoped_name);

// Fixed topic names.
inline constexpr const char* kControlTopic = "mechsim/control";
inline constexpr const char* kStatusTopic = "mechsim/status";
// The agent conversation of multi-host runs (idl/agent.idl, docs/hosts.md).
inline constexpr const char* kAgentRequestTopic = "mechsim/agent/request";
inline constexpr const char* kAgentReplyTopic = "mechsim/agent/reply";
// The best-effort twin of a data topic (Participant::create_redundant_writer).
inline std::string redundant_topic(const std::string& topic) { return topic + "/redundant"; }

}  // namespace mechsim::transport
