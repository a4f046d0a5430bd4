#include "ssh_agent_link.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "agent_frame.h"
#include "agent_protocol.h"

namespace mechsim::hostrun {

namespace {

// One argument for the remote shell ssh hands the command to: single-quoted.
std::string shell_quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string last_lines(const std::string& path, std::size_t count) {
  std::ifstream in(path);
  std::deque<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    lines.push_back(line);
    if (lines.size() > count) lines.pop_front();
  }
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : " | ") + l;
  return out;
}

class SshAgentLink : public AgentLink {
 public:
  explicit SshAgentLink(const std::vector<SshSession>& sessions) {
    for (const auto& s : sessions) open(s);
  }
  ~SshAgentLink() override {
    // Our end closed: ssh passes the end of stdin on, the agent stops its nodes and exits,
    // then ssh does. Waited for (the hosts are clean when the launcher returns), bounded.
    for (auto& s : sessions_)
      if (s.fd >= 0) ::shutdown(s.fd, SHUT_WR);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(8);
    for (auto& s : sessions_) {
      while (!s.reaped && std::chrono::steady_clock::now() < deadline) {
        reap(s);
        if (!s.reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      if (!s.reaped) {
        ::kill(s.pid, SIGTERM);
        ::waitpid(s.pid, nullptr, 0);
      }
      if (s.fd >= 0) ::close(s.fd);
    }
  }

  void send(const transport::AgentMessage& m) override {
    const std::string frame = encode_frame(m);
    for (auto& s : sessions_)
      if ((m.host == kAllAgents || m.host == s.address) && s.fd >= 0) {
        s.out += frame;
        flush(s);
      }
  }

  std::optional<transport::AgentMessage> take() override {
    for (auto& s : sessions_) {
      flush(s);
      read(s);
    }
    for (auto& s : sessions_) {
      if (s.fd < 0 && s.frames.buffered() == 0) continue;
      try {
        if (auto m = s.frames.next()) {
          m->host = s.address;  // the session says who sent it, not the message
          return m;
        }
      } catch (const FrameError& e) {
        close(s, std::string("the agent sent ") + e.what());
      }
    }
    return std::nullopt;
  }

  bool reaches(std::size_t agents) const override {
    std::size_t open = 0;
    for (const auto& s : sessions_) open += s.fd >= 0 ? 1 : 0;
    return open >= agents;
  }

  void wait(std::chrono::milliseconds timeout) override {
    std::vector<pollfd> fds;
    for (const auto& s : sessions_)
      if (s.fd >= 0) fds.push_back({s.fd, static_cast<short>(POLLIN | (s.out.empty() ? 0 : POLLOUT)), 0});
    if (fds.empty()) {
      std::this_thread::sleep_for(timeout);
      return;
    }
    ::poll(fds.data(), fds.size(), static_cast<int>(timeout.count()));
  }

  bool gone(const std::string& address) const override {
    for (const auto& s : sessions_)
      if (s.address == address) return s.fd < 0;
    return true;
  }

  std::string problem(const std::string& address) const override {
    for (const auto& s : sessions_)
      if (s.address == address) {
        const_cast<SshAgentLink*>(this)->reap(const_cast<Session&>(s));
        std::string why = s.closed_why;
        if (s.reaped) why += (why.empty() ? "" : "; ") + std::string("ssh ended (") + s.exit + ")";
        const std::string log = last_lines(s.log_path, 3);
        if (!log.empty()) why += (why.empty() ? "" : ": ") + log;
        return why.empty() ? "" : why + " (" + s.log_path + ")";
      }
    return "";
  }

 private:
  struct Session {
    std::string address, log_path;
    pid_t pid = -1;
    int fd = -1;
    std::string out;  // frames not yet written
    FrameReader frames;
    std::string closed_why;
    bool reaped = false;
    std::string exit;
  };

  void open(const SshSession& spec) {
    int pair[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0)
      throw std::runtime_error(std::string("socketpair for the ssh session to ") + spec.address + ": " + std::strerror(errno));
    const int log = ::open(spec.log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log < 0) throw std::runtime_error(spec.log_path + ": cannot create: " + std::strerror(errno));
    std::vector<std::string> storage = spec.argv;
    std::vector<char*> argv;
    for (auto& a : storage) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error(std::string("fork for ssh: ") + std::strerror(errno));
    if (pid == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (::getppid() != parent) ::_exit(127);
      ::dup2(pair[1], STDIN_FILENO);
      ::dup2(pair[1], STDOUT_FILENO);
      ::dup2(log, STDERR_FILENO);
      ::execvp(argv[0], argv.data());
      const char* msg = "mechsim: cannot execute ssh\n";
      ::write(STDERR_FILENO, msg, std::strlen(msg));
      ::_exit(127);
    }
    ::close(pair[1]);
    ::close(log);
    ::fcntl(pair[0], F_SETFL, ::fcntl(pair[0], F_GETFL) | O_NONBLOCK);
    Session s;
    s.address = spec.address;
    s.log_path = spec.log_path;
    s.pid = pid;
    s.fd = pair[0];
    sessions_.push_back(std::move(s));
  }

  void flush(Session& s) {
    while (s.fd >= 0 && !s.out.empty()) {
      const ssize_t n = ::send(s.fd, s.out.data(), s.out.size(), MSG_NOSIGNAL);
      if (n > 0) {
        s.out.erase(0, static_cast<std::size_t>(n));
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
      close(s, "the session does not take requests any more");
    }
  }

  void read(Session& s) {
    char buffer[65536];
    while (s.fd >= 0) {
      const ssize_t n = ::recv(s.fd, buffer, sizeof buffer, 0);
      if (n > 0) {
        s.frames.feed(buffer, static_cast<std::size_t>(n));
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
      close(s, "the session ended");
    }
  }

  void close(Session& s, const std::string& why) {
    if (s.fd < 0) return;
    ::close(s.fd);
    s.fd = -1;
    s.closed_why = why;
  }

  void reap(Session& s) {
    if (s.reaped) return;
    int status = 0;
    if (::waitpid(s.pid, &status, WNOHANG) != s.pid) return;
    s.reaped = true;
    s.exit = WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status)) : "signal " + std::to_string(WTERMSIG(status));
  }

  std::vector<Session> sessions_;
};

}  // namespace

std::vector<std::string> ssh_agent_command(const std::string& ssh_command, const std::string& ssh_config, const std::string& target,
                                           const std::string& remote_mechsim, int domain) {
  std::vector<std::string> argv;
  std::string rest = ssh_command.empty() ? std::string("ssh") : ssh_command;
  for (std::size_t at = 0; at < rest.size();) {
    const std::size_t end = rest.find(' ', at);
    const std::string word = rest.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (!word.empty()) argv.push_back(word);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  // No terminal, no password prompt: a run cannot wait for a person typing.
  argv.insert(argv.end(), {"-T", "-o", "BatchMode=yes"});
  if (!ssh_config.empty()) argv.insert(argv.end(), {"-F", ssh_config});
  argv.insert(argv.end(), {target, "--"});
  argv.push_back(shell_quoted(remote_mechsim) + " agent --stdio --domain " + std::to_string(domain));
  return argv;
}

std::unique_ptr<AgentLink> ssh_agent_link(const std::vector<SshSession>& sessions) { return std::make_unique<SshAgentLink>(sessions); }

}  // namespace mechsim::hostrun
