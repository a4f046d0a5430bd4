// .fmu archives with libzip, unpacked into a folder of their own under the temporary
// directory (the binary must be a file for dlopen) and removed with the FmuArchive.
#include "mechsim/fmi/archive.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

#include <zip.h>

namespace mechsim::fmi {

namespace fs = std::filesystem;

std::string host_platform(FmiVersion version) {
  // The standard's names for x86-64 Linux, the platform mechsim is built and tested on.
#if defined(__linux__) && defined(__x86_64__)
  return version == FmiVersion::fmi2 ? "linux64" : "x86_64-linux";
#else
#error "FMU import: name this host's binaries/ platform folder (FMI 2 and 3) here"
#endif
}

namespace {

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};
using ZipPtr = std::unique_ptr<zip_t, ZipCloser>;

ZipPtr open_zip(const FmuLabel& label) {
  std::error_code ec;
  if (!fs::is_regular_file(label.file, ec)) throw FmuError(label, "no such file");
  int code = 0;
  zip_t* z = zip_open(label.file.c_str(), ZIP_RDONLY, &code);
  if (z == nullptr) {
    if (code == ZIP_ER_NOZIP) throw FmuError(label, "is not a zip archive (an .fmu file is one)");
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string text = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw FmuError(label, "cannot open the archive: " + text);
  }
  return ZipPtr(z);
}

// An entry name that stays inside the folder: relative, no "..", no empty name.
bool safe_entry_name(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos) return false;
  std::stringstream parts(name);
  std::string part;
  while (std::getline(parts, part, '/'))
    if (part == "..") return false;
  return true;
}

void extract(zip_t* z, const fs::path& folder, const FmuLabel& label) {
  const zip_int64_t n = zip_get_num_entries(z, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* raw = zip_get_name(z, static_cast<zip_uint64_t>(i), 0);
    const std::string name = raw ? raw : "";
    if (!safe_entry_name(name))
      throw FmuError(label, "the archive entry '" + name + "' would land outside the FMU's folder; refused");
    const fs::path target = folder / name;
    if (name.back() == '/') {
      fs::create_directories(target);
      continue;
    }
    fs::create_directories(target.parent_path());
    zip_file_t* f = zip_fopen_index(z, static_cast<zip_uint64_t>(i), 0);
    if (f == nullptr)
      throw FmuError(label, "cannot read archive entry '" + name + "': " + zip_strerror(z));
    std::ofstream out(target, std::ios::binary);
    char buffer[1 << 16];
    zip_int64_t got = 0;
    while ((got = zip_fread(f, buffer, sizeof buffer)) > 0) out.write(buffer, got);
    const bool read_failed = got < 0;
    zip_fclose(f);
    if (read_failed || !out) throw FmuError(label, "cannot unpack archive entry '" + name + "'");
  }
}

fs::path make_temporary_folder(const FmuLabel& label) {
  std::string pattern = (fs::temp_directory_path() / "mechsim-fmu-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr)
    throw FmuError(label, "cannot create a temporary folder to unpack into under " +
                              fs::temp_directory_path().string());
  return pattern;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

}  // namespace

FmuArchive::FmuArchive(FmuLabel label) : label_(std::move(label)) {
  ZipPtr z = open_zip(label_);
  if (zip_name_locate(z.get(), "modelDescription.xml", 0) < 0)
    throw FmuError(label_, "the archive has no modelDescription.xml at its root");
  folder_ = make_temporary_folder(label_);
  try {
    extract(z.get(), folder_, label_);
    description_ = parse_model_description(read_file(folder_ / "modelDescription.xml"), label_);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder_ / "binaries", ec))
      if (entry.is_directory()) platforms_.push_back(entry.path().filename().string());
    std::sort(platforms_.begin(), platforms_.end());
  } catch (...) {
    std::error_code ec;
    fs::remove_all(folder_, ec);
    throw;
  }
}

FmuArchive::~FmuArchive() {
  std::error_code ec;  // a folder that cannot be removed is left, never an exception here
  fs::remove_all(folder_, ec);
}

const Interface& FmuArchive::require_interface(InterfaceKind kind) const {
  if (const Interface* i = description_.find_interface(kind)) return *i;
  std::vector<std::string> offered;
  for (const auto& i : description_.interfaces) offered.emplace_back(to_string(i.kind));
  throw FmuError(label_, "does not offer the " + std::string(to_string(kind)) + " interface (it offers " +
                             joined(offered) + ")");
}

fs::path FmuArchive::binary_path(InterfaceKind kind) const {
  const Interface& i = require_interface(kind);
  const std::string platform = host_platform(description_.version);
  const fs::path binary = folder_ / "binaries" / platform / (i.model_identifier + ".so");
  std::error_code ec;
  if (fs::is_regular_file(binary, ec)) return binary;
  const std::string present = platforms_.empty() ? "none: the archive has no binaries/ folder"
                                                 : joined(platforms_);
  throw FmuError(label_, "has no binary for this platform: binaries/" + platform + "/" + i.model_identifier +
                             ".so is missing (platforms in the archive: " + present + ")");
}

std::string FmuArchive::resource_location() const {
  const fs::path resources = folder_ / "resources";
  if (description_.version == FmiVersion::fmi2) return "file://" + resources.string();
  return resources.string() + "/";
}

}  // namespace mechsim::fmi
