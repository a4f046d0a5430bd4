// The transport-neutral field lists (topic_types.cpp) must mirror idl/*.idl exactly:
// same names, same order, same kinds. Parsed from the IDL text here so they cannot drift.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <regex>
#include <sstream>

#include "mechsim/transport/topic_types.h"

namespace mechsim::transport {
namespace {

struct IdlField {
  std::string type, name;
};

// Fields of `struct <name> { ... }` in an IDL file, without the leading Header.
std::vector<IdlField> idl_fields(const std::string& file, const std::string& struct_name) {
  std::ifstream in(std::string(MECHSIM_SOURCE_DIR) + "/idl/" + file);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const auto start = text.find("struct " + struct_name + " {");
  EXPECT_NE(start, std::string::npos) << struct_name << " not in " << file;
  const auto end = text.find("};", start);
  std::string body = text.substr(start, end - start);
  std::vector<IdlField> fields;
  const std::regex field(R"(^\s*(@final\s+)?([a-z ]+?|Header)\s+(\w+);)");
  std::istringstream lines(body);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, field) && m[2] != "Header") fields.push_back({m[2], m[3]});
  }
  return fields;
}

TEST(TopicTypes, FieldListsMirrorTheIdl) {
  ASSERT_FALSE(all_topic_types().empty());
  for (const TopicType* type : all_topic_types()) {
    const std::string short_name = type->idl_name.substr(type->idl_name.rfind(':') + 1);
    auto idl = idl_fields(type->idl_file, short_name);
    ASSERT_EQ(idl.size(), type->fields.size()) << type->idl_name;
    for (std::size_t i = 0; i < idl.size(); ++i) {
      EXPECT_EQ(idl[i].name, type->fields[i].name) << type->idl_name << " field " << i;
      const bool is_bool = idl[i].type == "boolean";
      EXPECT_EQ(is_bool, type->fields[i].kind == FieldKind::boolean) << type->idl_name << "." << idl[i].name;
      if (!is_bool) EXPECT_EQ(idl[i].type, "double") << type->idl_name << "." << idl[i].name;
    }
  }
}

TEST(TopicTypes, EveryIdlStructIsFinal) {
  for (const char* file : {"header.idl", "control.idl", "status.idl", "cam.idl", "follower.idl", "servo.idl", "tacho.idl", "slide.idl", "coupling.idl", "cvt.idl", "step.idl"}) {
    std::ifstream in(std::string(MECHSIM_SOURCE_DIR) + "/idl/" + file);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    // Every struct is annotated @final: the only extensibility Fast DDS 2.9 and Cyclone
    // agree on (docs/dds.md).
    std::size_t pos = 0, structs = 0;
    while ((pos = text.find("struct ", pos)) != std::string::npos) {
      ++structs;
      EXPECT_EQ(text.substr(pos >= 7 ? pos - 7 : 0, 7), "@final ") << file;
      pos += 7;
    }
    EXPECT_GT(structs, 0u) << file;
  }
}

TEST(TopicTypes, LookupByShortAndScopedName) {
  EXPECT_EQ(find_topic_type("CamState"), find_topic_type("mechsim::msg::CamState"));
  EXPECT_EQ(find_topic_type("NoSuchType"), nullptr);
}

}  // namespace

// docs/dds.md, 'Plausible samples', lists exactly the bounded fields of the topic table.
TEST(TopicTypes, PlausibleBoundsAreDocumented) {
  std::ifstream in(std::string(MECHSIM_SOURCE_DIR) + "/docs/dds.md");
  std::set<std::string> documented, declared;
  bool in_section = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Plausible samples";
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    std::istringstream row(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(row, cell, '|')) {
      const auto a = cell.find_first_not_of(" `"), b = cell.find_last_not_of(" `");
      if (a != std::string::npos) cells.push_back(cell.substr(a, b - a + 1));
    }
    ASSERT_EQ(cells.size(), 4u) << line;
    documented.insert(cells[0] + " " + cells[1] + " " + cells[2] + " " + cells[3]);
  }
  for (const TopicType* t : all_topic_types())
    for (const FieldInfo& f : t->fields)
      if (std::isfinite(f.min) || std::isfinite(f.max)) {
        std::ostringstream e;
        e << t->idl_name.substr(t->idl_name.rfind(':') + 1) << "." << f.name << " " << std::fixed << std::setprecision(0) << f.min << " "
          << f.max << " " << f.unit;
        declared.insert(e.str());
      }
  EXPECT_EQ(documented, declared);
}

}  // namespace mechsim::transport
