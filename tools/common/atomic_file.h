// Whole-file writes that never leave a half-written file behind.
#pragma once

#include <string>
#include <string_view>

namespace mechsim::tools {

// Writes `contents` to `path` through a temporary file in the same directory and a
// rename, so readers see either the old file or the complete new one. Throws
// std::runtime_error naming the path.
void write_file_atomically(const std::string& path, std::string_view contents);

}  // namespace mechsim::tools
