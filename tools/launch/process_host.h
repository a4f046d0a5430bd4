// Node processes on this machine (cosim/node_host.h): one process per node, or several
// nodes in one process (`participants.<p>.process: <group>`, docs/scenes.md).
// A process that stops stops every node in it; a restart (docs/faults.md) starts the whole
// process again, every member resuming from the checkpoint.
#pragma once

#include <string>
#include <vector>

#include "mechsim/cosim/node_command_line.h"
#include "mechsim/cosim/node_host.h"
#include "node_processes.h"

namespace mechsim::launch {

struct LocalProcess {
  std::string name;                  // the node's, or the group's
  std::vector<std::string> members;  // the nodes it runs
  std::string executable;
  cosim::NodeCommandLine command_line;  // a restart adds --resume
  std::string log_path;
  std::vector<std::string> environment;  // "NAME=value" on top of this process's
};

class ProcessNodeHost : public cosim::NodeHost {
 public:
  explicit ProcessNodeHost(std::vector<LocalProcess> processes) : planned_(std::move(processes)) {}

  std::vector<std::string> nodes() const override;
  void start_all() override;
  std::vector<cosim::NodeExit> poll() override;
  bool exited(const std::string& node) const override;
  std::string describe_exit(const std::string& node) const override;
  bool can_restart(const std::string&) const override { return true; }
  void restart(const std::string& node, std::uint64_t step, std::int32_t generation) override;
  void request_stop() override;
  void stop_all(double grace_s) override { processes_.stop_all(grace_s); }

  // The log file of the process that runs `node`.
  const std::string& log_of(const std::string& node) const { return planned(node).log_path; }

 private:
  const LocalProcess& planned(const std::string& node) const;
  std::vector<LocalProcess> planned_;
  hostrun::NodeProcesses processes_;
};

}  // namespace mechsim::launch
