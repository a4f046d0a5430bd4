#include "mechsim/transport/domain_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace mechsim::transport {

namespace {
constexpr const char* kLockDir = "/tmp/mechsim-domains";
constexpr int kPortBase = 7400, kDomainGain = 250;
}  // namespace

PortRange domain_ports(int domain) {
  const int first = kPortBase + kDomainGain * domain;
  return {first, first + kDomainGain - 1};
}

PortRange ephemeral_ports() {
  PortRange range{32768, 60999};
  std::ifstream in("/proc/sys/net/ipv4/ip_local_port_range");
  PortRange read;
  if (in >> read.first >> read.last && read.first <= read.last) range = read;
  return range;
}

std::vector<int> pickable_domains(PortRange ephemeral) {
  std::vector<int> domains;
  for (int d = kFirstFreeDomain; d <= kLastFreeDomain; ++d) {
    const PortRange ports = domain_ports(d);
    if (ports.last < ephemeral.first || ports.first > ephemeral.last) domains.push_back(d);
  }
  return domains;
}

DomainLock DomainLock::acquire() {
  ::mkdir(kLockDir, 01777);
  const std::vector<int> domains = pickable_domains();
  if (domains.empty()) {
    const PortRange e = ephemeral_ports();
    throw std::runtime_error("no DDS domain id in " + std::to_string(kFirstFreeDomain) + ".." +
                             std::to_string(kLastFreeDomain) + " has its ports (7400 + 250 d ...) outside the ephemeral port range " +
                             std::to_string(e.first) + ".." + std::to_string(e.last) +
                             " (/proc/sys/net/ipv4/ip_local_port_range); fix dds.domain in the scene");
  }
  std::random_device rd;
  const std::size_t offset = rd() % domains.size();
  for (std::size_t i = 0; i < domains.size(); ++i) {
    const int d = domains[(offset + i) % domains.size()];
    const std::string path = std::string(kLockDir) + "/" + std::to_string(d) + ".lock";
    int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return DomainLock(d, fd);
    ::close(fd);
  }
  throw std::runtime_error("no free DDS domain id: all " + std::to_string(domains.size()) +
                           " domains the launcher picks from are locked under /tmp/mechsim-domains");
}

DomainLock::DomainLock(DomainLock&& other) noexcept : domain_(other.domain_), fd_(other.fd_) { other.fd_ = -1; }

DomainLock::~DomainLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace mechsim::transport
