// The transport loop of one node: readiness, the start command, then the lock-step protocol
// of NodeStepper over the transport seam, with status heartbeats to the launcher. Its parts
// live in src/node/; the call order of one step is in docs/node-loop.md.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <cstdint>
#include <optional>
#include <string>

#include "mechsim/cosim/node_host.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

struct NodeRunOptions {
  std::string run_dir;              // where <node>.outputs.bin goes ("" = no output log)
  std::uint64_t run_id = 0;
  int domain = 0;                   // for messages
  // GUID of the launcher's control writer (transport::guid_text); "" = not checked (in process).
  std::string control_writer;
  double heartbeat_s = 0.1;         // status period while waiting or stepping
  double start_timeout_s = 120.0;   // give up when no start command arrives
  const std::atomic<bool>* stop_requested = nullptr;  // set by the node's signal handler
  // Restart with rollback (docs/faults.md): a node started again after a crash resumes from
  // its checkpoint of this step, in this generation, once the launcher sends resume.
  std::optional<std::uint64_t> resume_step;
  std::int32_t generation = 0;
  // Test seam (restart_test; the scene's `testing.lose_writes_after_resume`): the node leaves
  // out its first writes after a resume (the restored step's sample and the first
  // prediction), as a partner that had not yet matched its writers would miss them.
  bool lose_first_writes_after_resume = false;
  // Test seam (lost_sample_test; `testing.lose_write_of_step`): the node leaves out its
  // write of this step (both copies), as a sample lost and never repaired by DDS.
  std::optional<std::uint64_t> lose_write_of_step;
  // Test seam (restart_test; `testing.checkpoint_pause_step`, `testing.checkpoint_pause`): the
  // node stops this long halfway through writing its checkpoint of this step.
  std::optional<std::uint64_t> checkpoint_pause_step;
  double checkpoint_pause_s = 0.0;
  // Test seam (nc_loop_test; `testing.lose_failed_status`): a node that fails writes no
  // failed status, as one lost on the wire; its exit code still says what failed.
  bool lose_failed_status = false;
};

// One node's run as passes that never block (the node loop, docs/node-loop.md): a node
// process drives one with run_node; a process group's one executor thread drives all its
// members in turn (ThreadNodeHost), so that co-located members hand each other their
// samples in memory without a thread hand-off.
class NodeRun {
 public:
  NodeRun(ScenePlan& plan, const std::string& node_name, transport::Participant& participant, const NodeRunOptions& options);
  ~NodeRun();
  NodeRun(const NodeRun&) = delete;
  NodeRun& operator=(const NodeRun&) = delete;

  enum class Pass { progressed, idle, ended };
  // Takes what arrived, steps as far as the inputs allow, answers commands. Never throws:
  // a failure ends the run (reported on mechsim/status and stderr) with its exit code.
  Pass advance();
  // After an idle pass: waits, at most `longest`, as the node alone would: for samples
  // (the participant's waitset, or spinning in real-time mode) while it runs, else a nap
  // until the next look at its commands.
  void wait(std::chrono::nanoseconds longest);
  // Running (between start and the end), as opposed to waiting for start or resume.
  bool running() const;
  // node_exit_code (node_host.h) once advance() returned ended.
  int exit_code() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Runs the node to the end of the scene. Returns the process exit code (node_host.h,
// node_exit_code): done, failed, diverged, or stopped by the launcher or a signal. Errors
// are reported on mechsim/status and stderr.
int run_node(ScenePlan& plan, const std::string& node_name, transport::Participant& participant,
             const NodeRunOptions& options);

}  // namespace mechsim::cosim
