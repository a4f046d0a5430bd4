#include "fmu_files.h"

#include <stdexcept>
#include <system_error>

#include <stdlib.h>
#include <zip.h>

namespace mechsim::fmi::test {

namespace fs = std::filesystem;

std::string test_fmu(const std::string& stem) { return std::string(MECHSIM_TEST_FMU_DIR) + "/" + stem + ".fmu"; }

ScratchFolder::ScratchFolder() {
  std::string pattern = (fs::temp_directory_path() / "mechsim-fmi-test-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  folder_ = pattern;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ec;
  fs::remove_all(folder_, ec);
}

void write_zip(const fs::path& path, const std::vector<std::pair<std::string, std::string>>& entries) {
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (z == nullptr) throw std::runtime_error("zip_open failed for " + path.string());
  for (const auto& [name, content] : entries) {
    if (!name.empty() && name.back() == '/') {
      zip_dir_add(z, name.substr(0, name.size() - 1).c_str(), ZIP_FL_ENC_UTF_8);
      continue;
    }
    // libzip reads the buffer at zip_close: the content strings outlive it (entries is const&).
    zip_source_t* source = zip_source_buffer(z, content.data(), content.size(), 0);
    if (source == nullptr || zip_file_add(z, name.c_str(), source, ZIP_FL_ENC_UTF_8) < 0)
      throw std::runtime_error("zip_file_add failed for " + name + ": " + zip_strerror(z));
  }
  if (zip_close(z) != 0) throw std::runtime_error("zip_close failed for " + path.string());
}

std::vector<std::pair<std::string, std::string>> read_zip(const fs::path& path) {
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (z == nullptr) throw std::runtime_error("zip_open failed for " + path.string());
  std::vector<std::pair<std::string, std::string>> out;
  for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i) {
    const std::string name = zip_get_name(z, i, 0);
    std::string content;
    if (name.back() != '/') {
      zip_stat_t st;
      zip_stat_index(z, i, 0, &st);
      content.resize(st.size);
      zip_file_t* f = zip_fopen_index(z, i, 0);
      zip_fread(f, content.data(), st.size);
      zip_fclose(f);
    }
    out.emplace_back(name, content);
  }
  zip_discard(z);
  return out;
}

}  // namespace mechsim::fmi::test
