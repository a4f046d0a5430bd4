// Nodes as threads of this process (node_host.h): each with its own ScenePlan (its own
// blocks, as a node process builds its own) and its own participant, running the same
// run_node as a node process. run_inproc runs a whole scene so over the in-process
// transport; a process group (`participants.<p>.process`, docs/scenes.md) runs its
// members so, each its own DDS participant on the same topics as a node process.
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
#include "mechsim/transport/participant.h"

namespace mechsim::cosim {

class ThreadNodeHost : public NodeHost {
 public:
  // What one node thread needs, made on the calling thread before any thread starts.
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
  // Joins every thread: a thread cannot be killed, so a hung node is waited for.
  void stop_all(double grace_s) override;

  // Blocks until a node's thread finished or the timeout passed.
  void wait_for_exit(std::chrono::milliseconds timeout);
  // run_node's result: 0 done, 1 failed, 3 aborted; -1 still running.
  int exit_code(const std::string& node) const;

 private:
  struct Slot {
    std::string name;
    Parts parts;
    std::thread thread;
    std::atomic<int> exit_code{-1};
    bool reported = false;  // poll() returned it
  };
  const Slot& slot(const std::string& node) const;

  std::vector<std::string> names_;
  MakeParts make_parts_;
  NodeRunOptions options_;
  std::atomic<bool> stop_{false};
  std::vector<std::unique_ptr<Slot>> slots_;
  std::mutex exited_mutex_;
  std::condition_variable exited_;
};

}  // namespace mechsim::cosim
