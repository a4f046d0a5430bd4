// The clock of the node's waits and windows: the foreign-writer grace (SampleGate), the
// stall resend (StallResend), the windows after a resume (RollbackSession) and the
// partition grace (PartitionWatch). A run uses steady_now; the unit tests of these classes
// (tests/unit/node/) pass a clock of their own, so that a 4 s grace passes without a sleep.
#pragma once

#include <chrono>

namespace mechsim::cosim {

using SteadyNow = std::chrono::steady_clock::time_point (*)();

inline std::chrono::steady_clock::time_point steady_now() { return std::chrono::steady_clock::now(); }

}  // namespace mechsim::cosim
