#include "atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace mechsim::tools {

void write_file_atomically(const std::string& path, std::string_view contents) {
  // The pid and a per-process count keep concurrent writers (node processes, an agent's
  // threads) off each other's temporary file.
  static std::atomic<unsigned> count{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(count++);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
  int error = ok ? 0 : errno;
  if (std::fclose(f) != 0 && ok) {  // fclose flushes: a full disk shows up here
    ok = false;
    error = errno;
  }
  if (!ok) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int rename_errno = errno;
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(rename_errno));
  }
}

}  // namespace mechsim::tools
