// The supervision of one run, on the master side, wherever its nodes execute (node_host.h):
// the same piece for `mechsim launch` (processes, agents, process groups) and for in-process
// runs (run_inproc: threads). One cycle, in this order (docs/architecture.md):
//   1. start every node on its host;
//   2. barrier "ready": every node reports ready (matched end to end with its partners);
//   3. barrier "readers": the run's recorder, then every reader on the domain, matched;
//   4. send start on mechsim/control;
//   5. watch until every node is done: statuses, exits (a crash of a restartable node
//      starts a rollback to the newest common checkpoint), remote nodes gone silent for
//      the partition grace, local nodes silent for the hang timeout, progress;
//   6. on a failure: abort on mechsim/control, stop every node on every host.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/cosim/node_host.h"
#include "mechsim/transport/messages.h"
#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

// What the supervisor knows of one node from its statuses.
struct NodeWatch {
  transport::StatusMessage last;
  bool seen = false;
  std::chrono::steady_clock::time_point last_seen{};
  double done_at_s = -1;  // since start, from the node's done status
};
using NodeWatches = std::map<std::string, NodeWatch>;

// One restart with rollback (docs/faults.md), for the summary.
struct RestartRecord {
  std::string node, exit;
  std::uint64_t last_step = 0;      // the dead node's last step (output log or heartbeat)
  std::uint64_t rollback_step = 0;  // the checkpoint every node went back to
  int generation = 0;
  double detected_s = 0;            // since the start command: the supervisor saw the death
  double resumed_s = -1;            // every node held the checkpoint; resume sent
  double stepping_s = -1;           // every node's status past the checkpoint again
};

// The outcome of the distributed part of a run.
struct SupervisedRun {
  bool ok = false;
  int exit_code = 1;          // 1 failed, 130 interrupted
  std::string failed_node;
  std::string reason;
  bool diverged = false;      // the failure was a node's divergence guard
  std::uint64_t failed_step = 0;
  double wall_time_s = 0.0;   // start command -> all nodes done
};

struct SupervisorOptions {
  std::uint64_t run_id = 0;
  // Checkpoints (rollback) and output logs (a node's last step) are here; "" = none.
  std::string run_dir;
  double ready_timeout_s = 30.0;
  double hang_timeout_s = 30.0;       // a local node silent this long hung
  // From faults.partition_grace (config::fault_timings): a remote node silent for
  // silence_warning is named, one silent for partition_grace is unreachable.
  config::FaultTimings fault_timings = config::fault_timings(2.0);
  int restart_limit = 0;              // restarts per node
  std::uint64_t checkpoint_every = 0; // for the message when no checkpoint is held yet
  // The participants restarted after a crash (`restart`), where their host can restart them.
  std::vector<std::string> restartable;
  // The start command; its start_wall_ns is set when it is sent (real-time pacing).
  transport::ControlMessage start;
  // The grid's last step, for the message on a node that ended early (0: not known, adaptive).
  std::uint64_t last_step = 0;
  // Appended to the "not ready" failure, e.g. where the logs are.
  std::string not_ready_hint;
};

// The launcher's (or a test's) side of the supervision: every member may be left empty.
struct SupervisorHooks {
  // Nonzero: the signal that interrupted the run (SIGINT, SIGTERM).
  std::function<int()> interrupted;
  // A line for the user (warnings, restarts); "mechsim: " is not part of it.
  std::function<void(const std::string& line)> say;
  // The message that explains a node's exit, given what its last status said ("" when none).
  std::function<std::string(const std::string& node, const std::string& status_message)> exit_message;
  // After the ready barrier: "" or why the run's own recorder is not matched.
  std::function<std::string()> recorder_matched;
  // Readers on the domain a node's writer has not matched yet ("" when none): waited for
  // up to 10 s, then a warning.
  std::function<std::string(const NodeWatches&)> unmatched_readers;
  // Called about every 0.2 s while the nodes step, and once at a successful end.
  std::function<void(const NodeWatches&, double since_start_s, bool final_line)> progress;
};

// What the typed status says (idl/status.idl), one predicate each.
bool is_rolled_back(const transport::StatusMessage& status, std::uint64_t step, std::int32_t generation);
bool is_cannot_keep_up_warning(const transport::StatusMessage& status);
bool is_divergence(const transport::StatusMessage& status);

class Supervisor {
 public:
  // `participant` carries the control writer and status reader; every host outlives this.
  Supervisor(transport::Participant& participant, transport::ControlWriter& control, transport::StatusReader& status,
             std::vector<NodeHost*> hosts, SupervisorOptions options, SupervisorHooks hooks = {});
  // Steps 1-6 of the header; returns when every node is done or the run failed (then
  // every node is stopped).
  SupervisedRun run();

  // The statuses still in flight after run() (the nodes' last words once stopped).
  void take_final_statuses() { take_status(); }
  const NodeWatches& watches() const { return watch_; }
  const std::vector<RestartRecord>& restarts() const { return restart_log_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The nodes of every host, in start order.
  const std::vector<std::string>& nodes() const { return nodes_; }
  NodeHost& host_of(const std::string& node) const;
  // The node's last step: its output log's, else its last heartbeat's.
  std::uint64_t last_step_of(const std::string& node) const;
  // The step the node reached: its end record's (node_end_record.h), else last_step_of.
  std::uint64_t reached_step(const std::string& node) const;

 private:
  // The passes of run().
  void send_start();
  void supervise();
  void conclude();
  void note_done_times();
  void note_stepping_after_rollback();
  bool finish_if_all_exited();  // true once every node's process has exited (the run is ok)
  void take_status();
  void check_exits(bool running);
  bool reached_end(const std::string& node);
  std::string of_last_step() const;
  void roll_back();
  void watch_silence();
  bool wait_ready();
  bool wait_readers();
  void fail(const std::string& node, const std::string& reason, bool exit_says_diverged = false);
  void say(const std::string& line) const;
  void pump();
  double since_start() const;

  transport::Participant& participant_;
  transport::ControlWriter& control_;
  transport::StatusReader& status_;
  std::vector<NodeHost*> hosts_;
  SupervisorOptions opt_;
  SupervisorHooks hooks_;
  std::vector<std::string> nodes_;
  std::map<std::string, NodeHost*> host_of_;
  NodeWatches watch_;
  std::vector<std::string> warnings_;
  std::vector<RestartRecord> restart_log_;
  std::map<std::string, int> restarts_;  // per node
  std::vector<std::string> to_restart_;
  std::int32_t generation_ = 0;
  transport::ControlMessage start_;
  std::chrono::steady_clock::time_point started_{};
  SupervisedRun out_;
};

}  // namespace mechsim::cosim
