// A free DDS domain id for one run: domain d is taken while this process holds an
// exclusive flock on /tmp/mechsim-domains/<d>.lock, so concurrent runs on one machine
// never share a domain (and never see each other's samples). The lock dies with the
// process, so a crashed launcher frees its domain.
//
// Only domains whose well-known UDP ports lie outside the kernel's ephemeral port range are
// picked: a port in that range may already be held by any socket the kernel numbered itself
// (another run's unicast socket, a TCP connection), and the participant of the domain then
// fails to bind it ("failed to bind to ANY:53900: address in use" on domain 186).
#pragma once

#include <vector>

namespace mechsim::transport {

// The domains a launcher picks from (0 is left to other DDS applications' defaults; 232 is
// the highest valid one, 231 and 232 are left to hand-fixed runs).
inline constexpr int kFirstFreeDomain = 1, kLastFreeDomain = 230;

// The RTPS well-known ports of domain d: 7400 + 250 d and the 250 after it (both vendors;
// unicast ports of participant index i are 7410 + 250 d + 2 i and the one after it).
struct PortRange {
  int first = 0, last = 0;  // inclusive
};
PortRange domain_ports(int domain);

// The kernel's ephemeral port range (/proc/sys/net/ipv4/ip_local_port_range; Linux's default
// 32768..60999 when it cannot be read).
PortRange ephemeral_ports();

// The domains of kFirstFreeDomain..kLastFreeDomain whose ports miss `ephemeral`, in order
// (1..100 and 215..230 with Linux's default range).
std::vector<int> pickable_domains(PortRange ephemeral = ephemeral_ports());

class DomainLock {
 public:
  // Tries the pickable domains from a random start; throws std::runtime_error when all are
  // taken.
  static DomainLock acquire();
  DomainLock(DomainLock&& other) noexcept;
  DomainLock& operator=(DomainLock&&) = delete;
  ~DomainLock();
  int domain_id() const { return domain_; }

 private:
  DomainLock(int domain, int fd) : domain_(domain), fd_(fd) {}
  int domain_;
  int fd_;
};

}  // namespace mechsim::transport
