// Test helper: run a command as a child process with a timeout, capturing its output.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace mechsim::testing {

// Bytes of <node>.outputs.bin in the run folder under `runs` so far (0 before it exists): a
// node that runs beside the launcher shows the run's progress there while it goes on.
inline std::uintmax_t output_bytes(const std::filesystem::path& runs, const std::string& node) {
  std::error_code ec;
  if (!std::filesystem::exists(runs, ec)) return 0;
  for (const auto& e : std::filesystem::directory_iterator(runs, ec)) {
    const auto size = std::filesystem::file_size(e.path() / (node + ".outputs.bin"), ec);
    if (!ec) return size;
  }
  return 0;
}

struct CommandResult {
  int exit_code = -1;      // -1 when killed by a signal or timed out
  bool timed_out = false;
  double seconds = 0.0;
  std::string output;      // stdout and stderr interleaved
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Starts `argv` in the background with output to `log_path`; returns its pid.
inline pid_t spawn(const std::vector<std::string>& argv, const std::string& log_path) {
  std::vector<std::string> copy = argv;
  std::vector<char*> args;
  for (auto& a : copy) args.push_back(a.data());
  args.push_back(nullptr);
  pid_t pid = ::fork();
  if (pid == 0) {
    int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  return pid;
}

// Waits for `pid` up to `timeout_s`; kills it (SIGKILL) on timeout.
inline CommandResult wait_for(pid_t pid, const std::string& log_path, double timeout_s) {
  CommandResult r;
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  for (;;) {
    if (::waitpid(pid, &status, WNOHANG) == pid) break;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.seconds > timeout_s) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = slurp(log_path);
  return r;
}

// Stops a launcher the test leaves early (a failed assertion): SIGTERM stops its nodes.
// Set pid to -1 once the test waited for it.
struct StopOnExit {
  pid_t pid;
  ~StopOnExit() {
    if (pid <= 0) return;
    ::kill(pid, SIGTERM);
    wait_for(pid, "/dev/null", 15);
  }
};

// Waits until `path` exists (the event a test needs, e.g. a checkpoint being written);
// false after `timeout_s`, a guard against a hang and not a measurement.
inline bool wait_for_path(const std::filesystem::path& path, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!std::filesystem::exists(path)) {
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

inline CommandResult run(const std::vector<std::string>& argv, const std::string& log_path, double timeout_s = 120) {
  return wait_for(spawn(argv, log_path), log_path, timeout_s);
}

// Pids of live processes whose command line contains `needle` (zombies excluded).
// Never throws: processes end while /proc is read, so the scan uses the error_code
// overloads and starts again when the directory changed under it (restart_test once caught
// an exception here; launch_test's killed-launcher test once ended without reaching its
// last step in a way that fits one).
inline std::vector<pid_t> processes_mentioning(const std::string& needle) {
  std::vector<pid_t> found;
  for (int attempt = 0; attempt < 5; ++attempt) {
    found.clear();
    std::error_code ec;
    for (std::filesystem::directory_iterator it("/proc", ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename();
      if (name.find_first_not_of("0123456789") != std::string::npos) continue;
      std::string cmdline = slurp(it->path() / "cmdline");
      for (char& c : cmdline)
        if (c == '\0') c = ' ';
      std::string stat = slurp(it->path() / "stat");
      const bool zombie = stat.find(") Z ") != std::string::npos;
      if (!zombie && cmdline.find(needle) != std::string::npos && std::stoi(name) != ::getpid())
        found.push_back(std::stoi(name));
    }
    if (!ec) break;
  }
  return found;
}

}  // namespace mechsim::testing
