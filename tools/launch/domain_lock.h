// A free DDS domain id for one run: domain d is taken while this process holds an
// exclusive flock on /tmp/mechsim-domains/<d>.lock, so concurrent runs on one machine
// never share a domain (and never see each other's samples). The lock dies with the
// process, so a crashed launcher frees its domain.
#pragma once

namespace mechsim::launch {

// The domains a launcher picks from (0 is left to other DDS applications' defaults).
inline constexpr int kFirstFreeDomain = 1, kLastFreeDomain = 230;

class DomainLock {
 public:
  // Tries domains from a random start in 1..230; throws std::runtime_error when all are taken.
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

}  // namespace mechsim::launch
