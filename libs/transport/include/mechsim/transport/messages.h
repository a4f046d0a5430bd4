// Transport-neutral messages: what node logic and the launcher see instead of DDS types.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mechsim::transport {

// Carried by every sample: the run it belongs to and the base step it was computed for.
struct SampleHeader {
  std::uint64_t run_id = 0;
  std::uint64_t step = 0;
  double t = 0.0;
};

// rollback: return to the checkpoint of `step` and wait; resume: go on from there (both
// carry the rollback's generation; docs/faults.md, 'Restart with rollback').
enum class ControlCommand : std::int32_t { none = 0, start = 1, stop = 2, abort = 3, rollback = 4, resume = 5 };
enum class RunMode : std::int32_t { lockstep = 0, realtime = 1 };

struct ControlMessage {
  std::uint64_t run_id = 0;
  ControlCommand command = ControlCommand::none;
  double end_time = 0.0;
  double macro_step = 0.0;
  RunMode mode = RunMode::lockstep;
  double rtf = 1.0;
  std::int64_t start_wall_ns = 0;  // realtime mode: Unix time of step 0 (ns)
  std::uint64_t step = 0;          // rollback, resume: the checkpoint's step
  std::int32_t generation = 0;     // 0 until the first rollback, then 1, 2, ...
  // Not on the wire: the GUID of the writer that sent it (guid_text), filled by the reader
  // so a node can refuse commands that are not the launcher's; "" where none is known.
  std::string writer;
};

// An RTPS GUID (12-byte prefix, 4-byte entity id) as text, "<24 hex>:<8 hex>", the same for
// both vendors, so a node on one vendor can compare a writer on the other.
std::string guid_text(const unsigned char (&guid)[16]);

enum class NodeState : std::int32_t { starting = 0, ready = 1, running = 2, done = 3, failed = 4 };
const char* to_string(NodeState s);

// A condition a running node reports without stopping (the message words it for people).
enum class NodeWarning : std::int32_t { none = 0, cannot_keep_up = 1 };
// Why a failed node stopped (the message words it for people).
enum class NodeError : std::int32_t {
  none = 0,
  other = 1,               // anything not named below (bad input, a solver failure, ...)
  diverged = 2,            // the node's own divergence guard
  implausible_input = 3,   // a partner's sample outside its bounds: the partner diverged, or corrupt data
  partner_unreachable = 4, // no sample for longer than faults.partition_grace
  foreign_data = 5,        // a writer that does not belong to the run
  missed_deadline = 6,     // real-time mode, realtime.on_overrun: abort
};
// An error that points to an unstable coupling, for which a stable macro step is sought.
inline bool points_to_divergence(NodeError e) { return e == NodeError::diverged || e == NodeError::implausible_input; }

struct StatusMessage {
  SampleHeader header;  // step and t of the last published step
  std::string node;     // instance name (at most 64 characters on the wire)
  NodeState state = NodeState::starting;
  double wall_time = 0.0;  // s since the node process started
  std::int64_t solver_steps = 0;
  std::int64_t rhs_evals = 0;
  std::int64_t error_test_failures = 0;
  std::int64_t nonlinear_failures = 0;
  std::int64_t roots_found = 0;
  double last_step_size = 0.0;
  std::int32_t last_order = 0;
  double lateness_max = 0.0;   // realtime mode, s
  double lateness_p99 = 0.0;   // s
  std::int64_t missed_deadlines = 0;
  double rtf_window = 0.0;     // achieved real-time factor over the last second
  // Readers matched with the node's data writer, tools' readers included: the launcher
  // starts a run once each node has matched every reader on the domain (docs/recording.md).
  std::int32_t readers_matched = 0;
  std::string message;  // for people: the last error or warning (at most 256 characters on the wire)
  // Typed fields, what the launcher acts on (nothing in the protocol matches the message):
  std::int64_t rollback_step = -1;  // back at the checkpoint of this step, awaiting resume; -1 none
  std::int32_t generation = 0;      // the rollback generation the node is in
  NodeWarning warning = NodeWarning::none;
  NodeError error = NodeError::none;  // set with state failed
  // Holds the checkpoint of `step` for the rollback of `generation` and waits for resume.
  bool back_at(std::uint64_t step, std::int32_t gen) const {
    return state == NodeState::ready && rollback_step == static_cast<std::int64_t>(step) && generation == gen;
  }
};

// A message between a launcher and a host's `mechsim agent` (idl/agent.idl); `kind` and the
// meaning of the fields belong to the agent protocol (tools/hostrun/agent_protocol.h).
struct AgentMessage {
  std::uint64_t run_id = 0;
  std::uint64_t sequence = 0;
  std::int32_t kind = 0;
  std::string host;   // at most 64 characters on the wire
  std::string node;   // at most 64 characters on the wire
  std::string text;
  std::vector<std::byte> data;  // at most kAgentChunkBytes
};
inline constexpr std::size_t kAgentChunkBytes = 65536;

}  // namespace mechsim::transport
