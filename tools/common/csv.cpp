#include "csv.h"

#include <cstdio>
#include <stdexcept>

#include "atomic_file.h"

namespace mechsim::tools {
namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::vector<double>>& columns) {
  if (header.size() != columns.size()) {
    throw std::invalid_argument("write_csv " + path + ": " + std::to_string(header.size()) +
                                " header names for " + std::to_string(columns.size()) + " columns");
  }
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c].size() != rows) {
      throw std::invalid_argument("write_csv " + path + ": column '" + header[c] + "' has " +
                                  std::to_string(columns[c].size()) + " values, column '" +
                                  header.front() + "' has " + std::to_string(rows));
    }
  }
  std::string text;
  for (std::size_t c = 0; c < header.size(); ++c) text += (c ? "," : "") + csv_field(header[c]);
  text += '\n';
  char buf[32];
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      std::snprintf(buf, sizeof buf, "%.17g", columns[c][r]);
      if (c) text += ',';
      text += buf;
    }
    text += '\n';
  }
  write_file_atomically(path, text);
}

}  // namespace mechsim::tools
