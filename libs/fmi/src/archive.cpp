// .fmu archives with libzip: read from the zip's directory, unpacked on demand into the
// run's folder or a temporary one (archive.h).
#include "mechsim/fmi/archive.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string_view>
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

// The entries' names and their total unpacked size, from the zip's directory.
struct Directory {
  std::vector<std::string> names;
  std::uint64_t unpacked_bytes = 0;
};
Directory read_directory(zip_t* z, const FmuLabel& label) {
  Directory d;
  const zip_int64_t n = zip_get_num_entries(z, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(z, static_cast<zip_uint64_t>(i), 0, &st) != 0 || !(st.valid & ZIP_STAT_NAME))
      throw FmuError(label, "cannot read the archive's directory: " + std::string(zip_strerror(z)));
    const std::string name = st.name;
    if (!safe_entry_name(name))
      throw FmuError(label, "the archive entry '" + name + "' would land outside the FMU's folder; refused");
    if (st.valid & ZIP_STAT_SIZE) d.unpacked_bytes += st.size;
    d.names.push_back(name);
  }
  return d;
}

std::string bytes_text(double bytes) {
  char buf[64];
  if (bytes >= 1024.0 * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.2f GiB", bytes / (1024.0 * 1024 * 1024));
  else if (bytes >= 1024.0 * 1024) std::snprintf(buf, sizeof buf, "%.2f MiB", bytes / (1024.0 * 1024));
  else std::snprintf(buf, sizeof buf, "%.0f bytes", bytes);
  return buf;
}

std::string limits_text(const ArchiveLimits& limits) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "the limits are %s unpacked and a ratio of %g : 1 (raise them for this FMU with "
                "`unpack_limits: {size_mb: N, ratio: R}` beside its file in the scene, docs/fmi.md)",
                bytes_text(static_cast<double>(limits.max_unpacked_bytes)).c_str(), limits.max_ratio);
  return buf;
}

// Refuses, before anything is unpacked, an archive whose directory says it unpacks beyond the limits.
void check_limits(const Directory& d, std::uint64_t file_bytes, const ArchiveLimits& limits, const FmuLabel& label) {
  const double ratio = static_cast<double>(d.unpacked_bytes) / static_cast<double>(std::max<std::uint64_t>(file_bytes, 1));
  if (d.unpacked_bytes <= limits.max_unpacked_bytes && ratio <= limits.max_ratio) return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "unpacks to %s (%llu bytes) from a file of %s, a ratio of %.0f : 1; ",
                bytes_text(static_cast<double>(d.unpacked_bytes)).c_str(), static_cast<unsigned long long>(d.unpacked_bytes),
                bytes_text(static_cast<double>(file_bytes)).c_str(), ratio);
  throw FmuError(label, buf + limits_text(limits) + "; refused before unpacking");
}

// Unpacks every entry, counting what is written against the size limit (an entry's
// declared size may be false).
void extract(zip_t* z, const fs::path& folder, const ArchiveLimits& limits, const FmuLabel& label) {
  const zip_int64_t n = zip_get_num_entries(z, 0);
  std::uint64_t written = 0;
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
    bool too_large = false;
    while ((got = zip_fread(f, buffer, sizeof buffer)) > 0) {
      written += static_cast<std::uint64_t>(got);
      if ((too_large = written > limits.max_unpacked_bytes)) break;
      out.write(buffer, got);
    }
    const bool read_failed = got < 0;
    zip_fclose(f);
    if (too_large)
      throw FmuError(label, "unpacks to more than its directory says, past " +
                                bytes_text(static_cast<double>(limits.max_unpacked_bytes)) + " at entry '" + name + "'; " +
                                limits_text(limits) + "; refused");
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

std::string read_entry(zip_t* z, const char* name, const FmuLabel& label) {
  zip_file_t* f = zip_fopen(z, name, 0);
  if (f == nullptr) throw FmuError(label, std::string("cannot read archive entry '") + name + "': " + zip_strerror(z));
  std::string text;
  char buffer[1 << 16];
  zip_int64_t got = 0;
  while ((got = zip_fread(f, buffer, sizeof buffer)) > 0) text.append(buffer, static_cast<std::size_t>(got));
  zip_fclose(f);
  if (got < 0) throw FmuError(label, std::string("cannot read archive entry '") + name + "'");
  return text;
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

std::mutex g_root_mutex;
fs::path g_unpack_root;

// A folder name from the FMU's file and participant (letters, digits, '-', '_', '.').
std::string folder_key(const FmuLabel& label) {
  std::string key = fs::path(label.file).stem().string() + "-" + (label.participant.empty() ? "tool" : label.participant);
  for (char& c : key)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return key;
}

// Closes a file descriptor (and so drops its lock) on every way out.
struct LockedFile {
  int fd = -1;
  ~LockedFile() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

void set_unpack_root(const fs::path& root) {
  std::lock_guard lock(g_root_mutex);
  g_unpack_root = root;
}

fs::path unpack_root() {
  std::lock_guard lock(g_root_mutex);
  return g_unpack_root;
}

FmuArchive::FmuArchive(FmuLabel label, ArchiveLimits limits) : label_(std::move(label)), limits_(limits) {
  ZipPtr z = open_zip(label_);
  if (zip_name_locate(z.get(), "modelDescription.xml", 0) < 0)
    throw FmuError(label_, "the archive has no modelDescription.xml at its root");
  const Directory d = read_directory(z.get(), label_);
  std::error_code ec;
  check_limits(d, fs::file_size(label_.file, ec), limits_, label_);
  entries_ = d.names;
  description_ = parse_model_description(read_entry(z.get(), "modelDescription.xml", label_), label_);
  for (const std::string& name : entries_) {
    constexpr std::string_view prefix = "binaries/";
    if (!name.starts_with(prefix)) continue;
    const auto slash = name.find('/', prefix.size());
    if (slash == std::string::npos || slash == prefix.size()) continue;  // a file directly in binaries/
    const std::string platform = name.substr(prefix.size(), slash - prefix.size());
    if (std::find(platforms_.begin(), platforms_.end(), platform) == platforms_.end()) platforms_.push_back(platform);
  }
  std::sort(platforms_.begin(), platforms_.end());
}

FmuArchive::~FmuArchive() {
  if (!owns_folder_) return;  // the run's folder: the launcher removes it
  std::error_code ec;  // a folder that cannot be removed is left, never an exception here
  fs::remove_all(folder_, ec);
}

void FmuArchive::unpack() const {
  std::call_once(unpacked_, [this] {
    ZipPtr z = open_zip(label_);
    const fs::path root = unpack_root();
    if (root.empty()) {
      folder_ = make_temporary_folder(label_);
      owns_folder_ = true;
      try {
        extract(z.get(), folder_, limits_, label_);
      } catch (...) {
        std::error_code ec;
        fs::remove_all(folder_, ec);
        throw;
      }
      return;
    }
    // The run's folder for this FMU: unpacked by the first process under the lock, reused
    // by the others once its marker says it is whole (a process that died unpacking left none).
    std::error_code ec;
    fs::create_directories(root, ec);
    const std::string key = folder_key(label_);
    LockedFile lock{::open((root / (key + ".lock")).c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)};
    if (lock.fd < 0 || ::flock(lock.fd, LOCK_EX) != 0)
      throw FmuError(label_, "cannot lock " + (root / (key + ".lock")).string() + " to unpack into " + root.string());
    const fs::path folder = root / key, marker = root / (key + ".unpacked");
    if (!fs::exists(marker, ec)) {
      fs::remove_all(folder, ec);
      fs::create_directories(folder);
      try {
        extract(z.get(), folder, limits_, label_);
      } catch (...) {
        fs::remove_all(folder, ec);
        throw;
      }
      std::ofstream(marker) << label_.file << "\n";
    }
    folder_ = folder;
  });
}

const fs::path& FmuArchive::folder() const {
  unpack();
  return folder_;
}

const Interface& FmuArchive::require_interface(InterfaceKind kind) const {
  if (const Interface* i = description_.find_interface(kind)) return *i;
  std::vector<std::string> offered;
  for (const auto& i : description_.interfaces) offered.emplace_back(to_string(i.kind));
  throw FmuError(label_, "does not offer the " + std::string(to_string(kind)) + " interface (it offers " +
                             joined(offered) + ")");
}

void FmuArchive::check_binary(InterfaceKind kind) const {
  const Interface& i = require_interface(kind);
  const std::string platform = host_platform(description_.version);
  const std::string entry = "binaries/" + platform + "/" + i.model_identifier + ".so";
  if (std::find(entries_.begin(), entries_.end(), entry) != entries_.end()) return;
  const std::string present = platforms_.empty() ? "none: the archive has no binaries/ folder"
                                                 : joined(platforms_);
  throw FmuError(label_, "has no binary for this platform: " + entry + " is missing (platforms in the archive: " + present + ")");
}

fs::path FmuArchive::binary_path(InterfaceKind kind) const {
  check_binary(kind);
  return folder() / "binaries" / host_platform(description_.version) / (require_interface(kind).model_identifier + ".so");
}

std::string FmuArchive::resource_location() const {
  const fs::path resources = folder() / "resources";
  if (description_.version == FmiVersion::fmi2) return "file://" + resources.string();
  return resources.string() + "/";
}

}  // namespace mechsim::fmi
