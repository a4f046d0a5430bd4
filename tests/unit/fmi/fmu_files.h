// Files for the FMI tests: the test FMUs CMake builds (tests/fmus) and archives a test
// writes itself (libzip) for the cases that need no binary: not a zip, no description,
// malformed XML, FMI 1.0, ...
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace mechsim::fmi::test {

// build/tests/fmus/<stem>.fmu, e.g. test_fmu("lag_fmi2_cs").
std::string test_fmu(const std::string& stem);

// A folder under the temporary directory, removed with the object.
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  std::filesystem::path path(const std::string& name) const { return folder_ / name; }

 private:
  std::filesystem::path folder_;
};

// Writes a zip archive at `path` with the (name, content) entries, in order.
void write_zip(const std::filesystem::path& path, const std::vector<std::pair<std::string, std::string>>& entries);
// The entries of an existing archive (names ending in '/' are folders, content empty).
std::vector<std::pair<std::string, std::string>> read_zip(const std::filesystem::path& path);

}  // namespace mechsim::fmi::test
