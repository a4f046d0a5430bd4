#include "shared_library.h"

#include <dlfcn.h>

namespace mechsim::fmi {

SharedLibrary::SharedLibrary(const std::filesystem::path& path, std::string shown_path, const FmuLabel& label)
    : shown_path_(std::move(shown_path)), label_(label) {
  handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) {
    const char* why = dlerror();
    throw FmuError(label_, "cannot load its binary " + shown_path_ + ": " + (why ? why : "dlopen failed"));
  }
}

SharedLibrary::~SharedLibrary() {
  if (handle_ != nullptr) dlclose(handle_);
}

void* SharedLibrary::symbol(const std::string& name, const std::string& needed_for) const {
  dlerror();
  void* f = dlsym(handle_, name.c_str());
  if (f == nullptr)
    throw FmuError(label_, "its binary " + shown_path_ + " lacks the function " + name + " (needed for " +
                               needed_for + ")");
  return f;
}

}  // namespace mechsim::fmi
