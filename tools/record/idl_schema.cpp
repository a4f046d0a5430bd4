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

}  // namespace

std::string schema_text(const MessageLayout& layout) {
  return without_preprocessor_lines(file_text("header.idl")) + without_preprocessor_lines(file_text(layout.idl_file));
}

}  // namespace mechsim::recorder
