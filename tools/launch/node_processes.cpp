#include "node_processes.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace mechsim::launch {

std::string NodeProcess::describe_exit() const {
  if (!exited) return "running";
  if (signalled) return "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  return "exit code " + std::to_string(exit_code);
}

NodeProcesses::~NodeProcesses() { stop_all(1.0); }

void NodeProcesses::start(const std::string& name, const std::string& executable,
                          const std::vector<std::string>& args, const std::string& log_path) {
  int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log < 0) throw std::runtime_error(log_path + ": cannot create log: " + std::strerror(errno));
  std::vector<std::string> argv_storage{executable};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    // Child: die with the launcher; a launcher that died before prctl is caught by the check.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::execv(executable.c_str(), argv.data());
    const char* msg = "mechsim: cannot execute node executable\n";
    ::write(STDERR_FILENO, msg, std::strlen(msg));
    ::_exit(127);
  }
  ::close(log);
  processes_.push_back({name, executable, pid});
}

std::vector<NodeProcess*> NodeProcesses::poll() {
  std::vector<NodeProcess*> exited;
  for (auto& p : processes_) {
    if (p.exited) continue;
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
  for (auto& p : processes_)
    if (!p.exited) ::kill(p.pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s);
  while (!all_exited() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    poll();
  }
  for (auto& p : processes_)
    if (!p.exited) ::kill(p.pid, SIGKILL);
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

}  // namespace mechsim::launch
