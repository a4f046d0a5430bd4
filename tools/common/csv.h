// Time series for the run folder as CSV: one header line, one row per sample.
#pragma once

#include <string>
#include <vector>

namespace mechsim::tools {

// Writes columns of equal length under `header` (one name per column), values with
// %.17g so that they read back bit-exact. Header names containing ',', '"' or a line
// break are quoted (RFC 4180). Throws std::invalid_argument when the shapes disagree and
// std::runtime_error naming the path when the file cannot be written.
void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::vector<double>>& columns);

}  // namespace mechsim::tools
