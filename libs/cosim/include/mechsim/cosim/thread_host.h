// Nodes stepped by one thread of this process (node_host.h), each with its own ScenePlan
// (its own blocks, as a node process builds its own) and its own participant, running the
// same node loop (NodeRun) as a node process. The one executor thread polls the nodes in
// the order given (the scene's), as ROS 2's single-threaded executor polls a component
// container's nodes, and the nodes hand each other the samples of their topics in memory
// (transport::LocalHandoff): no serialization, no DDS wake-up, no thread hand-off between
// them. Every node still publishes its topics on its participant, for tools and readers in
// other processes. run_inproc runs a whole scene so over the in-process transport; a process
// group (`participants.<p>.process`, docs/scenes.md) runs its members so, each its own DDS
// participant on the same topics as a node process. docs/node-loop.md, "One executor per process".
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "mechsim/cosim/node_host.h"
#include "mechsim/cosim/node_runner.h"
#include "mechsim/cosim/scene_plan.h"
#include "mechsim/transport/local_handoff.h"
#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

class ThreadNodeHost : public NodeHost {
 public:
  // What one node needs, made on the calling thread before the executor starts.
  struct Parts {
    std::unique_ptr<ScenePlan> plan;
    std::unique_ptr<transport::Participant> participant;
    // This node's own options (e.g. its test seams); none: the host's. Either way the
    // node stops on this host's request_stop.
    std::optional<NodeRunOptions> options = std::nullopt;
  };
  using MakeParts = std::function<Parts(const std::string& node)>;
  // `options` serve every node; stop_requested is this host's (request_stop).
  ThreadNodeHost(std::vector<std::string> nodes, MakeParts make_parts, NodeRunOptions options);
  ~ThreadNodeHost() override;

  std::vector<std::string> nodes() const override { return names_; }
  void start_all() override;
  std::vector<NodeExit> poll() override;
  bool exited(const std::string& node) const override;
  std::string describe_exit(const std::string& node) const override;
  void request_stop() override;
  // Joins the executor thread: a thread cannot be killed, so a hung node is waited for.
  void stop_all(double grace_s) override;

  // Blocks until a node ended or the timeout passed.
  void wait_for_exit(std::chrono::milliseconds timeout);
  // run_node's result: 0 done, 1 failed, 3 aborted; -1 still running.
  int exit_code(const std::string& node) const;

 private:
  struct Slot {
    std::string name;
    Parts parts;
    NodeRunOptions options;    // what its NodeRun refers to
    bool external = false;     // some of its inputs come from outside this executor
    std::atomic<int> exit_code{-1};
    bool reported = false;     // poll() returned it
  };
  const Slot& slot(const std::string& node) const;
  void execute();
  void ended(Slot& slot, int code);

  std::vector<std::string> names_;
  MakeParts make_parts_;
  NodeRunOptions options_;
  std::atomic<bool> stop_{false};
  std::unique_ptr<transport::LocalHandoff> handoff_;
  std::vector<std::unique_ptr<Slot>> slots_;
  std::thread executor_;
  std::mutex exited_mutex_;
  std::condition_variable exited_;
};

}  // namespace mechsim::cosim
