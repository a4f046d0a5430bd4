#include "agent_stdio.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "agent_frame.h"
#include "elapsed.h"
#include "hosts.h"

namespace mechsim::agent {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// The SSH client that opened this session, for log lines ("root from 10.77.0.1 port 41220").
std::string ssh_client() {
  const char* user = std::getenv("USER");
  const char* client = std::getenv("SSH_CLIENT");  // "ADDRESS PORT LOCALPORT"
  std::string who = user ? user : "uid " + std::to_string(::getuid());
  if (client) {
    std::string c = client;
    const auto sp = c.find(' ');
    who += " from " + c.substr(0, sp);
    if (sp != std::string::npos) who += " port " + c.substr(sp + 1, c.find(' ', sp + 1) - sp - 1);
  } else {
    who += " (not over ssh)";
  }
  return "the session of " + who;
}

// The fd, moved off 0/1 so that nothing else in this process (or a node it starts) reads the
// requests or writes into the replies; 0 becomes /dev/null and 1 a copy of stderr.
int take_fd(int fd, int replacement) {
  const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, 3);
  if (moved < 0) throw std::runtime_error(std::string("cannot duplicate the session's file descriptor: ") + std::strerror(errno));
  ::dup2(replacement, fd);
  return moved;
}

void write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("the launcher's end of the session is closed");
    done += static_cast<std::size_t>(n);
  }
}

// A folder of this user's, 0700, that nobody else can have planted: refused when it
// exists with another owner or wider rights.
void make_private_dir(const fs::path& dir) {
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) throw std::runtime_error(dir.string() + ": cannot create: " + std::strerror(errno));
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::getuid() || (st.st_mode & 077) != 0)
    throw std::runtime_error(dir.string() + ": expected a folder of this user's with mode 0700 (it is not: remove it)");
}

}  // namespace

std::string session_work_dir() {
  return "/var/tmp/mechsim-agent-" + std::to_string(::getuid()) + "/ssh-" + std::to_string(::getpid());
}

int run_stdio_agent(const AgentOptions& options) {
  AgentOptions opt = options;
  try {
    catch_stop_signals(true);
    const int devnull = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int in = take_fd(STDIN_FILENO, devnull);
    const int out = take_fd(STDOUT_FILENO, STDERR_FILENO);
    const bool own_folder = opt.work_dir.empty();
    if (own_folder) {
      make_private_dir(fs::path(session_work_dir()).parent_path());
      opt.work_dir = session_work_dir();
    }
    make_private_dir(opt.work_dir);
    const auto local = hostrun::local_ipv4_addresses();
    const std::string sender = ssh_client();
    bool closed = false;  // the launcher's end: replies after it closed go nowhere
    AgentService service(opt, {local.begin(), local.end()}, "ssh", [&](transport::AgentMessage m) {
      if (closed) return;
      try {
        write_all(out, hostrun::encode_frame(m));
      } catch (const std::exception&) {
        closed = true;
      }
    });
    log_line("serving " + sender + " on domain " + std::to_string(opt.domain) + ", work folder " + opt.work_dir + ", at most " +
             std::to_string(opt.limits.max_processes) + " node processes, files of at most " +
             std::to_string(opt.limits.max_file_bytes) + " bytes");
    hostrun::FrameReader frames;
    std::string why = "the launcher closed the session";
    const auto started = Clock::now();
    char buffer[65536];
    while (!stop_signal() && !closed) {
      if (opt.exit_after_s > 0 && seconds_since(started) > opt.exit_after_s) {
        why = "the agent's time is up";
        break;
      }
      pollfd p{in, POLLIN, 0};
      const int ready = ::poll(&p, 1, 50);
      if (ready > 0) {
        const ssize_t n = ::read(in, buffer, sizeof buffer);
        if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) break;
        if (n > 0) frames.feed(buffer, static_cast<std::size_t>(n));
        try {
          while (auto m = frames.next()) service.handle(*m, sender);
        } catch (const hostrun::FrameError& e) {
          why = "refused " + sender + ": it sent " + e.what();
          log_line(why);
          break;
        }
      }
      service.tick();
    }
    if (stop_signal()) why = std::string("signal ") + strsignal(stop_signal());
    service.stop_all(why);
    log_line("session over: " + why);
    std::error_code ec;
    if (own_folder && !opt.keep_run_folders) fs::remove_all(opt.work_dir, ec);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim agent: %s\n", e.what());
    return 1;
  }
}

}  // namespace mechsim::agent
