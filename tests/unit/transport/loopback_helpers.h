// What the loopback tests of the transport share: a DDS domain of the test process's own,
// and waiting on a participant until a condition holds.
#pragma once

#include <unistd.h>

#include <chrono>
#include <functional>

#include "mechsim/transport/participant.h"

namespace mechsim::transport::testing {

// A domain id of its own per test process (tests run in parallel): 200 + pid % 30 is
// outside what most launcher runs pick first, and runs are isolated by run id anyway.
inline int test_domain() { return 200 + static_cast<int>(::getpid() % 30); }

// Waits on `p` (up to 5 s) until `done` holds; returns whether it did.
inline bool wait_until(Participant& p, const std::function<bool()>& done) {
  for (int i = 0; i < 500; ++i) {
    if (done()) return true;
    p.wait(std::chrono::milliseconds(10));
  }
  return done();
}

}  // namespace mechsim::transport::testing
