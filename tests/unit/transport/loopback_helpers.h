// What the loopback tests of the transport share: a DDS domain of the test process's own,
// and waiting on a participant until a condition holds.
#pragma once

#include <chrono>
#include <functional>

#include "mechsim/transport/domain_lock.h"
#include "mechsim/transport/participant.h"

namespace mechsim::transport::testing {

// A domain id of its own per test process (tests run in parallel, launcher runs beside
// them): the launcher's lock, held until the process ends, so no other test or run takes it.
inline int test_domain() {
  static const DomainLock lock = DomainLock::acquire();
  return lock.domain_id();
}

// Waits on `p` (up to 5 s) until `done` holds; returns whether it did.
inline bool wait_until(Participant& p, const std::function<bool()>& done) {
  for (int i = 0; i < 500; ++i) {
    if (done()) return true;
    p.wait(std::chrono::milliseconds(10));
  }
  return done();
}

}  // namespace mechsim::transport::testing
