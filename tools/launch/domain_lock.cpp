#include "domain_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <random>
#include <stdexcept>
#include <string>

namespace mechsim::launch {

namespace {
constexpr const char* kLockDir = "/tmp/mechsim-domains";
// Domain ids map to UDP ports 7400 + 250 d; 232 is the highest valid one. 0 is left to
// other DDS applications' defaults.
}  // namespace

DomainLock DomainLock::acquire() {
  ::mkdir(kLockDir, 01777);
  std::random_device rd;
  const int span = kLastFreeDomain - kFirstFreeDomain + 1;
  const int offset = static_cast<int>(rd() % span);
  for (int i = 0; i < span; ++i) {
    const int d = kFirstFreeDomain + (offset + i) % span;
    const std::string path = std::string(kLockDir) + "/" + std::to_string(d) + ".lock";
    int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return DomainLock(d, fd);
    ::close(fd);
  }
  throw std::runtime_error("no free DDS domain id: all of 1..230 are locked under /tmp/mechsim-domains");
}

DomainLock::DomainLock(DomainLock&& other) noexcept : domain_(other.domain_), fd_(other.fd_) { other.fd_ = -1; }

DomainLock::~DomainLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace mechsim::launch
