#include "idl_schema.h"

#include <sstream>
#include <stdexcept>

namespace mechsim::recorder {

namespace {

// Drops the preprocessor lines: #include (the header is inlined instead) and the include
// guard (#ifndef/#define/#endif), which an IDL reader without a preprocessor would choke on.
std::string without_preprocessor_lines(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line[first] == '#') continue;
    out += line + "\n";
  }
  return out;
}

const std::string& file_text(const std::string& name) {
  auto it = idl_files().find(name);
  if (it == idl_files().end()) throw std::logic_error("IDL file " + name + " was not compiled into the recorder");
  return it->second;
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

CdrKind kind_of(const std::string& type, const std::string& member) {
  if (type == "double") return CdrKind::f64;
  if (type == "float") return CdrKind::f32;
  if (type == "boolean") return CdrKind::boolean;
  if (type == "octet" || type == "uint8") return CdrKind::octet;
  if (type == "short" || type == "int16") return CdrKind::i16;
  if (type == "unsigned short" || type == "uint16") return CdrKind::u16;
  if (type == "long" || type == "int32") return CdrKind::i32;
  if (type == "unsigned long" || type == "uint32") return CdrKind::u32;
  if (type == "long long" || type == "int64") return CdrKind::i64;
  if (type == "unsigned long long" || type == "uint64") return CdrKind::u64;
  if (type == "string" || type.rfind("string<", 0) == 0) return CdrKind::string;
  throw std::logic_error("IDL member '" + member + "' has type '" + type + "', which the recorder cannot decode");
}

}  // namespace

std::vector<CdrField> struct_members(const std::string& idl_text, const std::string& name) {
  // The text without comments, then the body between "struct <name> {" and its "}".
  std::istringstream in(idl_text);
  std::string text;
  for (std::string line; std::getline(in, line);) text += line.substr(0, line.find("//")) + "\n";
  std::size_t open = std::string::npos;
  for (std::size_t at = text.find("struct " + name); at != std::string::npos; at = text.find("struct " + name, at + 1)) {
    const std::size_t after = at + 7 + name.size();
    const std::size_t brace = text.find_first_not_of(" \t\r\n", after);
    if (brace != std::string::npos && text[brace] == '{') {
      open = brace;
      break;
    }
  }
  if (open == std::string::npos) throw std::logic_error("no struct " + name + " in the IDL text");
  const std::size_t close = text.find('}', open);
  if (close == std::string::npos) throw std::logic_error("struct " + name + " is not closed");
  std::istringstream body(text.substr(open + 1, close - open - 1));
  std::vector<CdrField> fields;
  bool header_seen = false;
  for (std::string declaration; std::getline(body, declaration, ';');) {
    std::istringstream words(declaration);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    if (w.size() < 2) throw std::logic_error("struct " + name + ": cannot parse member '" + trimmed(declaration) + "'");
    const std::string member = w.back();
    std::string type;
    for (std::size_t i = 0; i + 1 < w.size(); ++i) type += (i ? " " : "") + w[i];
    if (!header_seen) {
      if (type != "Header") throw std::logic_error("struct " + name + " does not start with its Header");
      header_seen = true;
      continue;
    }
    fields.push_back({member, kind_of(type, name + "." + member)});
  }
  if (!header_seen) throw std::logic_error("struct " + name + " has no Header");
  return fields;
}

std::string schema_text(const MessageLayout& layout) {
  return without_preprocessor_lines(file_text("header.idl")) + without_preprocessor_lines(file_text(layout.idl_file));
}

}  // namespace mechsim::recorder
