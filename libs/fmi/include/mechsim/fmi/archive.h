// An .fmu file unpacked into a temporary folder that is removed with the object: the model
// description, the platforms the archive has binaries for, and the paths the binary and
// resources/ are loaded from.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mechsim/fmi/model_description.h"

namespace mechsim::fmi {

// The platform folder of this machine's binaries: "linux64" (FMI 2), "x86_64-linux" (FMI 3).
std::string host_platform(FmiVersion version);

class FmuArchive {
 public:
  // Unpacks `label.file` (libzip) and parses its modelDescription.xml. Refuses a file that
  // is missing or not a zip archive, an entry that would land outside the folder, and an
  // archive without modelDescription.xml at its root.
  explicit FmuArchive(FmuLabel label);
  ~FmuArchive();
  FmuArchive(const FmuArchive&) = delete;
  FmuArchive& operator=(const FmuArchive&) = delete;

  const FmuLabel& label() const { return label_; }
  const ModelDescription& description() const { return description_; }
  const std::filesystem::path& folder() const { return folder_; }
  // Platforms with a binaries/<platform>/ folder in the archive, sorted.
  const std::vector<std::string>& platforms() const { return platforms_; }
  // binaries/<host platform>/<model identifier>.so of `kind`. Refuses an interface the FMU
  // does not offer (naming those it does) and a missing binary for this platform (naming
  // the platforms present).
  std::filesystem::path binary_path(InterfaceKind kind) const;
  // resources/ as the standard hands it to instantiate (file URI in FMI 2, path with a
  // trailing slash in FMI 3); the folder need not exist.
  std::string resource_location() const;
  const Interface& require_interface(InterfaceKind kind) const;

 private:
  FmuLabel label_;
  std::filesystem::path folder_;
  ModelDescription description_;
  std::vector<std::string> platforms_;
};

}  // namespace mechsim::fmi
