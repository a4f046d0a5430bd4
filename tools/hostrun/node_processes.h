// The node processes of one run: started with their log files, watched, and stopped.
// Children get PR_SET_PDEATHSIG so they never outlive the launcher, even when it is killed.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mechsim::hostrun {

class AgentClient;

struct NodeProcess {
  std::string name;
  std::string executable;
  pid_t pid = -1;
  std::string host{};    // address of the agent that started it; "" = a child of this process
  std::string remote_exit{};  // a remote node's exit as its agent described it
  bool remote_reached_end = false;  // a remote node wrote its end record on its host
  bool exited = false;
  int exit_code = 0;     // valid when exited and !signalled
  bool signalled = false;
  int signal = 0;
  std::string describe_exit() const;  // "exit code 1", "killed by signal 9 (Killed)"
};

class NodeProcesses {
 public:
  ~NodeProcesses();  // stops whatever still runs
  // Starts `executable args...` with stdout and stderr appended to `log_path`, and the
  // "NAME=value" entries of `environment` set on top of this process's environment.
  void start(const std::string& name, const std::string& executable, const std::vector<std::string>& args,
             const std::string& log_path, const std::vector<std::string>& environment = {});
  // Starts an exited local node again (restart with rollback, docs/faults.md): the same
  // executable with these arguments, its log appended to.
  void restart(const std::string& name, const std::vector<std::string>& args, const std::string& log_path,
               const std::vector<std::string>& environment = {});
  // A node on another host, started by its agent (agent_client.h); watched and stopped
  // like a child. `agents` must outlive this object.
  void start_remote(const std::string& name, const std::string& address, const std::string& request, AgentClient& agents);
  // Reaps exited children without blocking; returns the ones that exited now.
  std::vector<NodeProcess*> poll();
  bool all_exited() const;
  // SIGTERM to all running, wait up to `grace_s`, then SIGKILL and reap.
  void stop_all(double grace_s);
  std::vector<NodeProcess>& processes() { return processes_; }
  const std::vector<NodeProcess>& processes() const { return processes_; }
  // Every process started after this may write files of at most `bytes` each (RLIMIT_FSIZE:
  // a larger write fails and the kernel sends SIGXFSZ); 0 = no limit of its own.
  void set_file_size_limit(std::uint64_t bytes) { file_size_limit_ = bytes; }
  // The process of node `name`; throws std::logic_error for a name that was never started.
  NodeProcess& find(const std::string& name);
  const NodeProcess& find(const std::string& name) const { return const_cast<NodeProcesses*>(this)->find(name); }

 private:
  pid_t spawn(const std::string& executable, const std::vector<std::string>& args, const std::string& log_path,
              const std::vector<std::string>& environment);
  std::vector<NodeProcess> processes_;
  AgentClient* agents_ = nullptr;
  std::uint64_t file_size_limit_ = 0;
};

}  // namespace mechsim::hostrun
