// The node processes of one run: started with their log files, watched, and stopped.
// Children get PR_SET_PDEATHSIG so they never outlive the launcher, even when it is killed.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace mechsim::launch {

struct NodeProcess {
  std::string name;
  std::string executable;
  pid_t pid = -1;
  bool exited = false;
  int exit_code = 0;     // valid when exited and !signalled
  bool signalled = false;
  int signal = 0;
  std::string describe_exit() const;  // "exit code 1", "killed by signal 9 (Killed)"
};

class NodeProcesses {
 public:
  ~NodeProcesses();  // stops whatever still runs
  // Starts `executable args...` with stdout and stderr appended to `log_path`.
  void start(const std::string& name, const std::string& executable, const std::vector<std::string>& args,
             const std::string& log_path);
  // Reaps exited children without blocking; returns the ones that exited now.
  std::vector<NodeProcess*> poll();
  bool all_exited() const;
  // SIGTERM to all running, wait up to `grace_s`, then SIGKILL and reap.
  void stop_all(double grace_s);
  std::vector<NodeProcess>& processes() { return processes_; }

 private:
  std::vector<NodeProcess> processes_;
};

}  // namespace mechsim::launch
