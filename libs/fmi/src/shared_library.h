// A shared object opened with dlopen (RTLD_LOCAL: every FMU exports the same names) and
// closed with the object; functions resolved by name, a missing one refused by name.
#pragma once

#include <filesystem>
#include <string>

#include "mechsim/fmi/error.h"

namespace mechsim::fmi {

class SharedLibrary {
 public:
  SharedLibrary(const std::filesystem::path& path, std::string shown_path, const FmuLabel& label);
  ~SharedLibrary();
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;

  // The function `name` of type F (a function type such as fmi2DoStepTYPE).
  template <typename F>
  F* function(const std::string& name, const std::string& needed_for) const {
    return reinterpret_cast<F*>(symbol(name, needed_for));
  }

 private:
  void* symbol(const std::string& name, const std::string& needed_for) const;
  void* handle_ = nullptr;
  std::string shown_path_;  // as inside the archive: binaries/<platform>/<id>.so
  FmuLabel label_;
};

}  // namespace mechsim::fmi
