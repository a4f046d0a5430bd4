// The recorder's CDR decoder: hand-built buffers whose member offsets are written out
// here from the CDR rules (XCDR1: 8-byte members 8-aligned; XCDR2: 4-aligned; both byte
// orders), malformed buffers, the layouts against the transport's field lists, and the
// schema text. Exact comparisons throughout: decoding moves bytes, it computes nothing.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

#include "cdr_decoder.h"
#include "idl_schema.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::recorder {
namespace {

// A CDR buffer under construction: encapsulation header, then values put at payload
// offsets given by the test (not computed by any alignment code).
class Buffer {
 public:
  Buffer(std::uint16_t encapsulation, std::size_t payload_size, bool big_endian)
      : bytes_(4 + payload_size, std::byte{0}), big_endian_(big_endian) {
    bytes_[0] = std::byte(encapsulation >> 8);
    bytes_[1] = std::byte(encapsulation & 0xff);
  }
  template <class T>
  void put(std::size_t payload_offset, T value) {
    std::byte b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    std::memcpy(bytes_.data() + 4 + payload_offset, b, sizeof(T));
  }
  void put_string(std::size_t payload_offset, const std::string& s) {
    put<std::uint32_t>(payload_offset, static_cast<std::uint32_t>(s.size() + 1));
    std::memcpy(bytes_.data() + 4 + payload_offset + 4, s.c_str(), s.size() + 1);
  }
  std::vector<std::byte>& bytes() { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
  bool big_endian_;
};

void put_header(Buffer& b) {
  b.put<std::uint64_t>(0, 0x0123456789abcdefULL);
  b.put<std::uint64_t>(8, 4711);
  b.put<double>(16, 4.711);
}

void expect_header(const transport::SampleHeader& h) {
  EXPECT_EQ(h.run_id, 0x0123456789abcdefULL);
  EXPECT_EQ(h.step, 4711u);
  EXPECT_EQ(h.t, 4.711);
}

// FollowerState: 4 doubles, a boolean, 7 doubles. The boolean at payload offset 56 pushes
// the next double to 64 under XCDR1 and to 60 under XCDR2.
std::vector<std::byte> follower_state(std::uint16_t encapsulation, bool big_endian, std::size_t after_bool) {
  Buffer b(encapsulation, after_bool + 7 * 8, big_endian);
  put_header(b);
  for (int i = 0; i < 4; ++i) b.put<double>(24 + 8 * i, 0.5 + i);
  b.put<std::uint8_t>(56, 1);
  for (int i = 0; i < 7; ++i) b.put<double>(after_bool + 8 * i, -1.25 * (i + 1));
  return b.bytes();
}

void expect_follower_state(const DecodedSample& s) {
  expect_header(s.header);
  const MessageLayout& l = *find_layout("FollowerState");
  ASSERT_EQ(s.values.size(), 12u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(std::get<double>(s.values[i]), 0.5 + i) << l.fields[i].name;
  EXPECT_EQ(std::get<bool>(s.values[l.field_index("contact")]), true);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(std::get<double>(s.values[5 + i]), -1.25 * (i + 1)) << l.fields[5 + i].name;
}

TEST(CdrDecoder, Xcdr1LittleEndianAlignsDoublesToEight) {
  expect_follower_state(decode_sample(follower_state(0x0001, false, 64), *find_layout("FollowerState")));
}

TEST(CdrDecoder, Xcdr1BigEndian) {
  expect_follower_state(decode_sample(follower_state(0x0000, true, 64), *find_layout("FollowerState")));
}

TEST(CdrDecoder, Xcdr2AlignsDoublesToFourInBothByteOrders) {
  expect_follower_state(decode_sample(follower_state(0x0007, false, 60), *find_layout("FollowerState")));
  expect_follower_state(decode_sample(follower_state(0x0006, true, 60), *find_layout("FollowerState")));
}

TEST(CdrDecoder, StatusWithStringsAndIntegers) {
  // idl/status.idl, XCDR1 LE. node "follower" (length 9 with the NUL) at 24, chars 28..36;
  // state (long) at 40; wall_time at 48; five long longs 56..88; last_step_size 96;
  // last_order 104; lateness_max 112, lateness_p99 120, missed_deadlines 128, rtf_window
  // 136; readers_matched (long) 144; message length at 148, chars 152..155; rollback_step
  // (long long) 160; generation 168, warning 172, error 176 (longs).
  Buffer b(0x0001, 180, false);
  put_header(b);
  b.put_string(24, "follower");
  b.put<std::int32_t>(40, 2);
  b.put<double>(48, 0.25);
  for (int i = 0; i < 5; ++i) b.put<std::int64_t>(56 + 8 * i, -(i + 1) * 1000000000000LL);
  b.put<double>(96, 1e-4);
  b.put<std::int32_t>(104, 3);
  b.put<double>(112, 0.5e-3);
  b.put<double>(120, 0.25e-3);
  b.put<std::int64_t>(128, 17);
  b.put<double>(136, 0.97);
  b.put<std::int32_t>(144, 4);
  b.put_string(148, "a\"b");
  b.put<std::int64_t>(160, 300);
  b.put<std::int32_t>(168, 2);
  b.put<std::int32_t>(172, 1);
  b.put<std::int32_t>(176, 4);
  const MessageLayout& l = *find_layout("mechsim::msg::Status");
  const DecodedSample s = decode_sample(b.bytes(), l);
  expect_header(s.header);
  EXPECT_EQ(std::get<std::string>(s.values[l.field_index("node")]), "follower");
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("state")]), 2);
  EXPECT_EQ(std::get<double>(s.values[l.field_index("wall_time")]), 0.25);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("solver_steps")]), -1000000000000LL);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("roots_found")]), -5000000000000LL);
  EXPECT_EQ(std::get<double>(s.values[l.field_index("last_step_size")]), 1e-4);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("last_order")]), 3);
  EXPECT_EQ(std::get<double>(s.values[l.field_index("lateness_max")]), 0.5e-3);
  EXPECT_EQ(std::get<double>(s.values[l.field_index("lateness_p99")]), 0.25e-3);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("missed_deadlines")]), 17);
  EXPECT_EQ(std::get<double>(s.values[l.field_index("rtf_window")]), 0.97);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("readers_matched")]), 4);
  EXPECT_EQ(std::get<std::string>(s.values[l.field_index("message")]), "a\"b");
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("rollback_step")]), 300);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("generation")]), 2);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("warning")]), 1);
  EXPECT_EQ(std::get<std::int64_t>(s.values[l.field_index("error")]), 4);
}

TEST(CdrDecoder, OtherScalarKindsAlignToTheirSize) {
  // A struct of the kinds mechsim does not use yet, as the IDL parser reads them: octet
  // at 24, short at 26, unsigned short 28, float 32, unsigned long 36, unsigned long long 40.
  const std::vector<CdrField> fields = struct_members(
      "module m { @final struct S {\n Header header;\n octet a; short b;\n unsigned short c;\n"
      " float d; // comment\n unsigned long e;\n unsigned long long f;\n };\n};",
      "S");
  ASSERT_EQ(fields.size(), 6u);
  EXPECT_EQ(fields[2].kind, CdrKind::u16);
  EXPECT_EQ(fields[5].kind, CdrKind::u64);
  Buffer b(0x0001, 48, false);
  put_header(b);
  b.put<std::uint8_t>(24, 200);
  b.put<std::int16_t>(26, -300);
  b.put<std::uint16_t>(28, 60000);
  b.put<float>(32, 1.5f);
  b.put<std::uint32_t>(36, 4000000000u);
  b.put<std::uint64_t>(40, 18000000000000000000ULL);
  const DecodedSample s = decode_sample(b.bytes(), MessageLayout{"m::S", "", fields});
  EXPECT_EQ(std::get<std::uint64_t>(s.values[0]), 200u);
  EXPECT_EQ(std::get<std::int64_t>(s.values[1]), -300);
  EXPECT_EQ(std::get<std::uint64_t>(s.values[2]), 60000u);
  EXPECT_EQ(std::get<double>(s.values[3]), 1.5);
  EXPECT_EQ(std::get<std::uint64_t>(s.values[4]), 4000000000u);
  EXPECT_EQ(std::get<std::uint64_t>(s.values[5]), 18000000000000000000ULL);
  EXPECT_THROW(struct_members("struct T {\n Header header;\n sequence<double> x;\n};", "T"), std::logic_error);
  EXPECT_THROW(struct_members("struct T {\n double x;\n};", "T"), std::logic_error);
}

TEST(CdrDecoder, RefusesMalformedBuffers) {
  const MessageLayout& l = *find_layout("FollowerState");
  auto good = follower_state(0x0001, false, 64);
  auto short_one = good;
  short_one.resize(good.size() - 1);
  EXPECT_THROW(decode_sample(short_one, l), CdrError);
  EXPECT_THROW(decode_header(std::span(good).first(3)), CdrError);
  auto parameter_list = good;  // PL_CDR_LE: a mutable type, never a mechsim one
  parameter_list[1] = std::byte{0x03};
  EXPECT_THROW(decode_sample(parameter_list, l), CdrError);
  auto bad_bool = good;
  bad_bool[4 + 56] = std::byte{2};
  EXPECT_THROW(decode_sample(bad_bool, l), CdrError);

  Buffer status(0x0001, 40, false);
  put_header(status);
  status.put<std::uint32_t>(24, 4);
  std::memcpy(status.bytes().data() + 4 + 28, "abcd", 4);  // no NUL where the length says
  EXPECT_THROW(decode_sample(status.bytes(), *find_layout("Status")), CdrError);
}

TEST(CdrDecoder, HeaderAloneDecodesFromAnyType) {
  expect_header(decode_header(follower_state(0x0007, false, 60)));
}

TEST(MessageLayouts, DataTypesMirrorTheTransportFieldLists) {
  for (const transport::TopicType* t : transport::all_topic_types()) {
    const MessageLayout* l = find_layout(t->idl_name);
    ASSERT_NE(l, nullptr) << t->idl_name;
    EXPECT_EQ(l->idl_file, t->idl_file);
    ASSERT_EQ(l->fields.size(), t->fields.size()) << t->idl_name;
    for (std::size_t i = 0; i < t->fields.size(); ++i) {
      EXPECT_EQ(l->fields[i].name, t->fields[i].name);
      EXPECT_EQ(l->fields[i].kind, t->fields[i].kind == transport::FieldKind::boolean ? CdrKind::boolean : CdrKind::f64);
    }
  }
  EXPECT_EQ(find_layout("CamState"), find_layout("mechsim::msg::CamState"));
  // The IDL says the same as the transport's field lists.
  for (const MessageLayout& l : all_layouts()) {
    // FmuOutputs: its members are sequences, its fields an FMU's (fmu_participant_test).
    if (l.sequences) continue;
    const std::vector<CdrField> parsed = struct_members(idl_files().at(l.idl_file), l.type_name.substr(l.type_name.rfind(':') + 1));
    ASSERT_EQ(parsed.size(), l.fields.size()) << l.type_name;
    for (std::size_t i = 0; i < parsed.size(); ++i) {
      EXPECT_EQ(parsed[i].name, l.fields[i].name) << l.type_name;
      EXPECT_EQ(parsed[i].kind, l.fields[i].kind) << l.type_name << "." << l.fields[i].name;
    }
  }
  EXPECT_NE(find_layout("Control"), nullptr);
  EXPECT_EQ(find_layout("Unknown"), nullptr);
}

// FmuOutputs (idl/fmu.idl), written by hand as XCDR1 little endian: header, then reals {1.5},
// integers {-7}, booleans {true, false}, each sequence a uint32 length and its elements
// aligned to their size. With the names of a channel's "mechsim.fields", and without.
TEST(CdrDecoder, FmuOutputsByTheFieldsOfItsFmu) {
  std::vector<std::byte> b(4 + 54, std::byte{0});
  b[1] = std::byte{0x01};
  const auto put = [&](std::size_t at, const auto& v) { std::memcpy(b.data() + 4 + at, &v, sizeof v); };
  put(0, std::uint64_t{42});
  put(8, std::uint64_t{3});
  put(16, 0.003);
  put(24, std::uint32_t{1});
  put(32, 1.5);  // aligned to 8
  put(40, std::uint32_t{1});
  put(44, std::int32_t{-7});
  put(48, std::uint32_t{2});
  b[4 + 52] = std::byte{1};
  const MessageLayout named = fmu_layout_from_text("y:f64,impacts:i32,contact:boolean,faulted:boolean");
  EXPECT_EQ(fields_text(named), "y:f64,impacts:i32,contact:boolean,faulted:boolean");
  const DecodedSample s = decode_sample(b, named);
  EXPECT_EQ(s.header.step, 3u);
  ASSERT_EQ(s.values.size(), 4u);
  EXPECT_EQ(as_number(s.values[0]), 1.5);
  EXPECT_EQ(as_number(s.values[1]), -7.0);
  EXPECT_EQ(to_text(s.values[2]), "true");
  EXPECT_EQ(to_text(s.values[3]), "false");
  const MessageLayout unnamed = unnamed_fmu_layout(b);
  ASSERT_EQ(unnamed.fields.size(), 4u);
  EXPECT_EQ(unnamed.fields[0].name, "reals[0]");
  EXPECT_EQ(unnamed.fields[3].name, "booleans[1]");
  // Another FMU's field list does not fit the sample: refused, not misread.
  EXPECT_THROW(decode_sample(b, fmu_layout_from_text("y:f64,z:f64")), CdrError);
  EXPECT_THROW(decode_sample(b, fmu_layout_from_text("y:f64")), CdrError);
  EXPECT_THROW(fmu_layout_from_text("y:float"), CdrError);
  // The channel metadata picks the names; without it the generic layout has none.
  EXPECT_EQ(channel_layout("mechsim::msg::FmuOutputs", {{kFieldsMetadataKey, "y:f64"}})->fields.size(), 1u);
  EXPECT_TRUE(channel_layout("mechsim::msg::FmuOutputs", {})->fields.empty());
  EXPECT_FALSE(channel_layout("Unknown", {}).has_value());
}

TEST(IdlSchema, IsSelfContainedIdlWithoutPreprocessorLines) {
  for (const MessageLayout& l : all_layouts()) {
    const std::string text = schema_text(l);
    const std::string short_name = l.type_name.substr(l.type_name.rfind(':') + 1);
    EXPECT_NE(text.find("struct Header"), std::string::npos) << l.type_name;
    EXPECT_NE(text.find("struct " + short_name + " "), std::string::npos) << l.type_name;
    EXPECT_LT(text.find("struct Header"), text.find("struct " + short_name + " ")) << "Header must come first";
    EXPECT_EQ(text.find("\n#"), std::string::npos) << text;
    EXPECT_NE(text[0], '#');
    for (const auto& f : l.fields) EXPECT_NE(text.find(" " + f.name + ";"), std::string::npos) << l.type_name << "." << f.name;
  }
}

}  // namespace
}  // namespace mechsim::recorder
