#include "node_processes.h"

#include "agent_client.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace mechsim::hostrun {

std::string NodeProcess::describe_exit() const {
  if (!exited) return "running";
  if (!host.empty()) return remote_exit;
  if (signalled) return "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  return "exit code " + std::to_string(exit_code);
}

NodeProcesses::~NodeProcesses() { stop_all(1.0); }

void NodeProcesses::start(const std::string& name, const std::string& executable,
                          const std::vector<std::string>& args, const std::string& log_path,
                          const std::vector<std::string>& environment) {
  const pid_t pid = spawn(executable, args, log_path, environment);
  processes_.push_back({name, executable, pid});
}

void NodeProcesses::restart(const std::string& name, const std::vector<std::string>& args, const std::string& log_path,
                            const std::vector<std::string>& environment) {
  for (auto& p : processes_)
    if (p.name == name) {
      if (!p.exited || !p.host.empty()) throw std::logic_error("restart of node '" + name + "', which is running or remote");
      const pid_t pid = spawn(p.executable, args, log_path, environment);
      p = NodeProcess{name, p.executable, pid};
      return;
    }
  throw std::logic_error("restart of an unknown node '" + name + "'");
}

pid_t NodeProcesses::spawn(const std::string& executable, const std::vector<std::string>& args, const std::string& log_path,
                           const std::vector<std::string>& environment) {
  int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log < 0) throw std::runtime_error(log_path + ": cannot create log: " + std::strerror(errno));
  std::vector<std::string> argv_storage{executable};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The child's environment, built before fork: the child of a threaded process may only
  // call async-signal-safe functions, which setenv is not.
  std::vector<std::string> env_storage;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    const std::string key = entry.substr(0, entry.find('='));
    bool replaced = false;
    for (const std::string& o : environment) replaced = replaced || o.substr(0, o.find('=')) == key;
    if (!replaced) env_storage.push_back(entry);
  }
  env_storage.insert(env_storage.end(), environment.begin(), environment.end());
  std::vector<char*> envp;
  for (auto& e : env_storage) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t parent = ::getpid();
  const rlim_t file_size_limit = static_cast<rlim_t>(file_size_limit_);
  pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    // Child: die with the launcher; a launcher that died before prctl is caught by the check.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    if (file_size_limit > 0) {
      const rlimit limit{file_size_limit, file_size_limit};
      ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::execve(executable.c_str(), argv.data(), envp.data());
    const char* msg = "mechsim: cannot execute node executable\n";
    ::write(STDERR_FILENO, msg, std::strlen(msg));
    ::_exit(127);
  }
  ::close(log);
  return pid;
}

void NodeProcesses::start_remote(const std::string& name, const std::string& address, const std::string& request,
                                 AgentClient& agents) {
  agents_ = &agents;
  agents.start(name, address, request);
  NodeProcess p{name, "(agent on " + address + ")"};
  p.host = address;
  processes_.push_back(p);
}

std::vector<NodeProcess*> NodeProcesses::poll() {
  std::vector<NodeProcess*> exited;
  if (agents_ != nullptr)
    for (const RemoteExit& e : agents_->take_exits())
      for (auto& p : processes_)
        if (p.name == e.node && !p.host.empty() && !p.exited) {
          p.exited = true;
          p.exit_code = e.exit_code;
          p.signalled = e.signalled;
          p.signal = e.signal;
          p.remote_exit = e.describe;
          p.remote_reached_end = e.reached_end;
          exited.push_back(&p);
        }
  for (auto& p : processes_) {
    if (p.exited || !p.host.empty()) continue;
    int status = 0;
    pid_t r = ::waitpid(p.pid, &status, WNOHANG);
    if (r == p.pid) {
      p.exited = true;
      p.signalled = WIFSIGNALED(status);
      p.signal = p.signalled ? WTERMSIG(status) : 0;
      p.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      exited.push_back(&p);
    }
  }
  return exited;
}

bool NodeProcesses::all_exited() const {
  for (const auto& p : processes_)
    if (!p.exited) return false;
  return true;
}

void NodeProcesses::stop_all(double grace_s) {
  poll();
  bool remote_running = false;
  for (auto& p : processes_) remote_running = remote_running || (!p.exited && !p.host.empty());
  if (remote_running) agents_->stop_all();
  for (auto& p : processes_)
    if (!p.exited && p.host.empty()) ::kill(p.pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s);
  while (!all_exited() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    poll();
  }
  for (auto& p : processes_)
    if (!p.exited && p.host.empty()) ::kill(p.pid, SIGKILL);
  // An agent stops its nodes with the same grace, then reports: give it that long again.
  const auto remote_deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s + 3.0);
  while (remote_running && !all_exited() && std::chrono::steady_clock::now() < remote_deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    poll();
  }
  for (auto& p : processes_)
    if (!p.exited && !p.host.empty()) {
      p.exited = true;
      p.exit_code = -1;
      p.remote_exit = "no exit report from the agent on " + p.host + " (its heartbeat timeout stops the node)";
    }
  for (auto& p : processes_)
    if (!p.exited) {
      int status = 0;
      ::waitpid(p.pid, &status, 0);
      p.exited = true;
      p.signalled = WIFSIGNALED(status);
      p.signal = p.signalled ? WTERMSIG(status) : 0;
      p.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
}

NodeProcess& NodeProcesses::find(const std::string& name) {
  for (auto& p : processes_)
    if (p.name == name) return p;
  throw std::logic_error("no node process named '" + name + "'");
}

}  // namespace mechsim::hostrun
