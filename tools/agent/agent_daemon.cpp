#include "agent_daemon.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "elapsed.h"
#include "hosts.h"
#include "install_paths.h"
#include "mechsim/config/scene.h"
#include "mechsim/transport/backends.h"

namespace mechsim::agent {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// The work folder is this agent's alone: a second agent on it would overwrite the DDS
// configuration the first one's nodes read (their own address) and hand back, then remove,
// the first one's node files. An flock dies with the process, so a killed agent frees it.
int lock_work_dir(const AgentOptions& opt) {
  fs::create_directories(opt.work_dir);
  const fs::path lock = fs::path(opt.work_dir) / "agent.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(lock.string() + ": cannot open: " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = read_whole_file(lock.string());
    ::close(fd);
    throw std::runtime_error("work folder " + opt.work_dir + " is in use by another mechsim agent (" +
                             (holder.empty() ? std::string("see ") + lock.string() : holder) +
                             "): give each agent a folder of its own with --work-dir, or leave it out (default: one "
                             "folder per address and domain; docs/hosts.md)");
  }
  const std::string me = "pid " + std::to_string(::getpid()) + ", address " +
                         (opt.address.empty() ? std::string("loopback") : opt.address) + ", domain " + std::to_string(opt.domain);
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size()))
    throw std::runtime_error(lock.string() + ": cannot write: " + std::strerror(errno));
  return fd;
}

bool loopback(const std::string& address) { return address.empty() || address.rfind("127.", 0) == 0; }

int serve(AgentOptions opt) {
  catch_stop_signals(false);
  if (const std::string why = unauthenticated_daemon_problem(opt); !why.empty()) throw std::runtime_error(why);
  if (opt.work_dir.empty()) opt.work_dir = default_work_dir(opt.address, opt.domain);
  const int lock_fd = lock_work_dir(opt);
  std::set<std::string> addresses;
  const auto local = hostrun::local_ipv4_addresses();
  if (!opt.address.empty()) {
    if (std::find(local.begin(), local.end(), opt.address) == local.end())
      throw std::runtime_error("--address " + opt.address + " is not an address of this host (it has: " +
                               hostrun::join(local, ", ") + ")");
    addresses.insert(opt.address);
    transport::UnicastNetwork network{opt.address, opt.peers};
    network.peers.push_back(opt.address);
    hostrun::set_environment(hostrun::write_unicast_dds_files((fs::path(opt.work_dir) / "dds").string(), network));
  } else {
    addresses.insert("127.0.0.1");
    hostrun::configure_dds_environment();
  }
  const std::string vendor = opt.vendor.empty() ? config::default_dds_vendor() : opt.vendor;
  auto participant = transport::create_participant(vendor, opt.domain);
  auto replies = participant->create_agent_writer(transport::kAgentReplyTopic);
  auto requests = participant->create_agent_reader(transport::kAgentRequestTopic);
  AgentService service(opt, addresses, participant->vendor(), [&](transport::AgentMessage m) { replies->write(m); });
  log_line("serving domain " + std::to_string(opt.domain) + " on " + hostrun::join({addresses.begin(), addresses.end()}, ", ") + " (" +
           vendor + "), work folder " + opt.work_dir + ", heartbeat timeout " + std::to_string(opt.heartbeat_timeout_s) +
           " s, at most " + std::to_string(opt.limits.max_processes) + " node processes" +
           (loopback(opt.address) ? "" : "; UNAUTHENTICATED: anyone on this network can command it (--allow-unauthenticated)"));
  const auto started = Clock::now();
  while (!stop_signal()) {
    if (opt.exit_after_s > 0 && seconds_since(started) > opt.exit_after_s) break;
    participant->wait(std::chrono::milliseconds(50));
    // DDS tells a request's writer by GUID only, which the message does not carry: the log
    // names the domain and the host the request claims.
    while (auto m = requests->take()) service.handle(*m, "a DDS writer on domain " + std::to_string(opt.domain) + " (claiming host '" + m->host + "')");
    service.tick();
  }
  service.stop_all(stop_signal() ? "the agent is stopping" : "the agent's time is up");
  log_line("stopped");
  ::close(lock_fd);
  return 0;
}

}  // namespace

std::string default_work_dir(const std::string& address, int domain) {
  return std::string(kWorkDirRoot) + "/" + (address.empty() ? std::string("loopback") : address) + "-domain" + std::to_string(domain);
}

std::string unauthenticated_daemon_problem(const AgentOptions& opt) {
  if (loopback(opt.address) || opt.allow_unauthenticated) return "";
  return "refused to serve --address " + opt.address +
         ": the DDS agent authenticates nobody, so anyone on that network could start processes on this host, read and stop "
         "runs. Across hosts the launcher reaches each host over SSH (hosts.<h>.ssh, no daemon: docs/hosts.md); to run this "
         "daemon on a network you trust anyway, add --allow-unauthenticated";
}

int run_agent(const AgentOptions& options) {
  try {
    return serve(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim agent: %s\n", e.what());
    return 1;
  }
}

}  // namespace mechsim::agent
