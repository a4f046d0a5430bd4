// The @mcap/core npm reader (read_mcap.mjs and its node_modules) the MCAP tests run, as
// installed by tools/install-test-deps.sh into MCAP_READER_WORK_DIR (build/mcap-reader),
// pinned by package-lock.json. The tests never touch the network: when the reader is not
// installed, or installed from another lock file, every test that needs it fails at once
// with one line saying what to run (a fresh machine without registry access used to spend
// 70-145 s per test in npm retries).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace mechsim::testing::npm_reader {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline bool in_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  const std::string dirs = path;
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    if (::access((std::filesystem::path(dirs.substr(start, end - start)) / program).c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// "" when `work` holds read_mcap.mjs and node_modules installed from the lock file in
// `source`; otherwise the one line to show. Looks at files only: no npm, no network.
inline std::string problem(const std::filesystem::path& source = MCAP_READER_SOURCE_DIR,
                           const std::filesystem::path& work = MCAP_READER_WORK_DIR) {
  const std::string run = "run tools/install-test-deps.sh (it needs the npm registry once)";
  if (!std::filesystem::exists(work / "node_modules" / "@mcap" / "core") || !std::filesystem::exists(work / "read_mcap.mjs"))
    return "the @mcap/core MCAP reader is not installed in " + work.string() + ": " + run;
  if (read_text(work / ".installed-package-lock.json") != read_text(source / "package-lock.json") ||
      read_text(work / "read_mcap.mjs") != read_text(source / "read_mcap.mjs"))
    return "the @mcap/core MCAP reader in " + work.string() + " was installed from another package-lock.json: " + run;
  return "";
}

}  // namespace mechsim::testing::npm_reader
