// An .fmu file: its model description and the platforms it has binaries for, read from the
// zip without unpacking, and, once code is to be loaded from it, its files unpacked into a
// folder (the binary must be a file for dlopen).
//
// Where it unpacks (docs/fmi.md, "Unpacking"): with an unpack root set for the process
// (set_unpack_root: a node sets <run folder>/fmu), into <root>/<FMU>-<participant>, once
// per host and run: the first process unpacks under a lock, the others and restarts reuse
// the folder, and the launcher removes the root when the run ends, however its processes
// ended. Without one (tests, tools on a single file), into a mechsim-fmu-XXXXXX folder of
// the temporary directory, removed with the object.
//
// Archive limits, checked on the zip's directory before a byte is unpacked and again while
// unpacking (a directory can lie): the total unpacked size and the ratio of unpacked size to
// the archive's file size. A 2 MB FMU with a 2 GiB file of zeros is refused with the numbers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "mechsim/fmi/model_description.h"

namespace mechsim::fmi {

// The platform folder of this machine's binaries: "linux64" (FMI 2), "x86_64-linux" (FMI 3).
std::string host_platform(FmiVersion version);

// Defaults no real FMU meets (a large one unpacks to a few hundred MB of tables at a ratio
// of 10-50 : 1); a scene raises them per FMU (`unpack_limits`, docs/fmi.md).
struct ArchiveLimits {
  std::uint64_t max_unpacked_bytes = std::uint64_t{2} << 30;  // 2 GiB
  double max_ratio = 200.0;  // unpacked bytes per byte of the .fmu file
};

// Where this process's FMU archives unpack from now on ("" = the temporary directory).
void set_unpack_root(const std::filesystem::path& root);
std::filesystem::path unpack_root();

class FmuArchive {
 public:
  // Opens `label.file` (libzip) and parses its modelDescription.xml from the zip. Refuses a
  // file that is missing or not a zip archive, an entry that would land outside the folder,
  // an archive without modelDescription.xml at its root, and one beyond `limits`.
  explicit FmuArchive(FmuLabel label, ArchiveLimits limits = {});
  ~FmuArchive();
  FmuArchive(const FmuArchive&) = delete;
  FmuArchive& operator=(const FmuArchive&) = delete;

  const FmuLabel& label() const { return label_; }
  const ModelDescription& description() const { return description_; }
  // The unpacked folder (unpacks on the first call).
  const std::filesystem::path& folder() const;
  // Platforms with a binaries/<platform>/ folder in the archive, sorted.
  const std::vector<std::string>& platforms() const { return platforms_; }
  // Refuses an interface the FMU does not offer (naming those it does) and a missing
  // binaries/<host platform>/<model identifier>.so (naming the platforms present), from the
  // zip's directory: nothing is unpacked.
  void check_binary(InterfaceKind kind) const;
  // The unpacked binary of `kind` (check_binary first; unpacks on the first call).
  std::filesystem::path binary_path(InterfaceKind kind) const;
  // resources/ as the standard hands it to instantiate (file URI in FMI 2, path with a
  // trailing slash in FMI 3); the folder need not exist. Unpacks on the first call.
  std::string resource_location() const;
  const Interface& require_interface(InterfaceKind kind) const;

 private:
  void unpack() const;
  FmuLabel label_;
  ArchiveLimits limits_;
  ModelDescription description_;
  std::vector<std::string> platforms_;
  std::vector<std::string> entries_;  // every entry name, as in the zip
  mutable std::once_flag unpacked_;
  mutable std::filesystem::path folder_;
  mutable bool owns_folder_ = false;  // a temporary folder of this object's (not the run's)
};

}  // namespace mechsim::fmi
