// The node's waits for the launcher: ready (matched with every partner), then the start
// command; after a rollback, the resume. Heartbeats go on meanwhile; no sample is taken.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>

#include "control_inbox.h"
#include "node_endpoints.h"
#include "node_status.h"

namespace mechsim::cosim {

// Reports ready once the node is matched with every partner, then waits for the launcher's
// `awaited` command (start; resume for a restarted node) of `generation`. nullopt: the run
// was stopped or aborted meanwhile. Throws when no such command comes within timeout_s.
std::optional<transport::ControlMessage> await_start(NodeEndpoints& io, ControlInbox& control, NodeStatus& status,
                                                     transport::ControlCommand awaited, std::int32_t generation,
                                                     double timeout_s, const std::atomic<bool>* stop_requested);

// Waits for the resume of `generation` after a rollback; false when the run is stopped meanwhile.
bool await_resume(ControlInbox& control, NodeStatus& status, std::int32_t generation, const std::atomic<bool>* stop_requested);

}  // namespace mechsim::cosim
