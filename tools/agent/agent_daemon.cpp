#include "agent_daemon.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "agent_protocol.h"
#include "atomic_file.h"
#include "hosts.h"
#include "mechsim/config/scene.h"
#include "mechsim/catalog/catalog.h"
#include "mechsim/cosim/node_command_line.h"
#include "mechsim/transport/backends.h"
#include "mechsim/transport/network_config.h"
#include "node_processes.h"
#include "install_paths.h"
#include "elapsed.h"

namespace mechsim::agent {

namespace fs = std::filesystem;
using hostrun::AgentKind;
using hostrun::kAllAgents;
using hostrun::kGroupType;
using hostrun::kHelloPeriodS;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

namespace {

std::atomic<int> g_stop{0};
void on_signal(int sig) { g_stop.store(sig); }


void log_line(const std::string& text) {
  std::fprintf(stderr, "mechsim agent: %s\n", text.c_str());
  std::fflush(stderr);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Atomically: see Agent::start_node.
void write_file(const fs::path& path, const std::string& text) { tools::write_file_atomically(path.string(), text); }

// One run a launcher asked this agent to take part in.
struct AgentRun {
  std::uint64_t run_id = 0;
  fs::path folder;
  hostrun::NodeProcesses processes;
  std::map<std::string, std::uint64_t> log_sent;  // node -> bytes of its log already sent
  std::set<std::string> exit_reported;
  Clock::time_point last_heartbeat = Clock::now();
  double heartbeat_timeout_s = 5.0;
};

class Agent {
 public:
  explicit Agent(AgentOptions o) : opt_(std::move(o)) {
    if (opt_.work_dir.empty()) opt_.work_dir = default_work_dir(opt_.address, opt_.domain);
  }
  ~Agent() {
    if (lock_fd_ >= 0) ::close(lock_fd_);
  }
  int run();

 private:
  void send(transport::AgentMessage m) {
    m.host = opt_.address.empty() ? "127.0.0.1" : opt_.address;
    m.sequence = ++sequence_;
    replies_->write(m);
  }
  void reply(std::uint64_t run_id, AgentKind kind, const std::string& node, const std::string& text) {
    transport::AgentMessage m;
    m.run_id = run_id;
    m.kind = static_cast<std::int32_t>(kind);
    m.node = node;
    m.text = text;
    send(std::move(m));
  }
  bool meant_for_me(const std::string& host) const {
    return host == kAllAgents || addresses_.count(host) > 0;
  }
  void handle(const transport::AgentMessage& m);
  void start_node(const transport::AgentMessage& m);
  void stream_logs(AgentRun& run);
  void report_exits(AgentRun& run);
  void collect(AgentRun& run);
  void stop_run(AgentRun& run, const std::string& why);
  void hello();
  void lock_work_dir();

  AgentOptions opt_;
  int lock_fd_ = -1;
  std::set<std::string> addresses_;
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::AgentWriter> replies_;
  std::unique_ptr<transport::AgentReader> requests_;
  std::map<std::uint64_t, std::unique_ptr<AgentRun>> runs_;
  std::set<std::uint64_t> finished_;  // collected: requests for them are answered, not acted on
  std::uint64_t sequence_ = 0;
};

void Agent::hello() {
  char hostname[256] = "";
  ::gethostname(hostname, sizeof hostname - 1);
  json j{{"addresses", json(std::vector<std::string>(addresses_.begin(), addresses_.end()))},
         {"hostname", hostname},
         {"pid", static_cast<long>(::getpid())},
         {"vendor", participant_->vendor()},
         {"runs", runs_.size()}};
  reply(0, AgentKind::hello, "", j.dump());
}

void Agent::start_node(const transport::AgentMessage& m) {
  auto& slot = runs_[m.run_id];
  if (!slot) {
    slot = std::make_unique<AgentRun>();
    slot->run_id = m.run_id;
    slot->heartbeat_timeout_s = opt_.heartbeat_timeout_s;
  }
  AgentRun& run = *slot;
  run.last_heartbeat = Clock::now();
  for (const auto& p : run.processes.processes())
    if (p.name == m.node) {  // a repeated request: it was started, say so again
      reply(m.run_id, AgentKind::started, m.node, json{{"pid", p.pid}}.dump());
      return;
    }
  const json request = json::parse(m.text, nullptr, false);
  auto refuse = [&](const std::string& why) {
    log_line("refused node '" + m.node + "' of run " + std::to_string(m.run_id) + ": " + why);
    reply(m.run_id, AgentKind::refused, m.node, why);
  };
  if (request.is_discarded() || !request.is_object()) return refuse("the start request is not a JSON object");
  const std::string type = request.value("type", "");
  // Only the node executables of the catalog, from this build: never a path the request names.
  // "fmu": the node of a participant of type fmu, whose node type each plan makes (docs/fmi.md);
  // "node_group": a process group, its participants named in "members" (docs/scenes.md).
  if (cosim::find_node_type(type) == nullptr && type != "fmu" && type != kGroupType)
    return refuse("'" + type + "' is not a mechsim node type");
  std::vector<std::string> members{m.node};
  if (type == kGroupType) {
    if (!request.contains("members") || !request["members"].is_array() || request["members"].empty())
      return refuse("a node_group request names its participants in \"members\" (a non-empty list)");
    members.clear();
    for (const auto& member : request["members"]) {
      if (!member.is_string()) return refuse("\"members\" must be a list of participant names");
      members.push_back(member.get<std::string>());
    }
  }
  const std::string folder_name = request.value("run_folder", "");
  if (folder_name.empty() || folder_name.find('/') != std::string::npos || folder_name[0] == '.')
    return refuse("run_folder must be a plain folder name, got '" + folder_name + "'");
  std::vector<std::string> names = members;
  names.push_back(m.node);
  for (const std::string& name : names)
    if (name.empty() || name.find('/') != std::string::npos || name[0] == '.')
      return refuse("a participant (or process group) name must be a plain name, got '" + name + "'");
  if (request.value("domain", -1) != opt_.domain)
    return refuse("the request is for domain " + std::to_string(request.value("domain", -1)) + ", this agent serves " +
                  std::to_string(opt_.domain));
  std::string executable;
  try {
    executable = hostrun::node_executable(type);
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
  try {
    run.folder = fs::path(opt_.work_dir) / folder_name;
    fs::create_directories(run.folder);
    // Replaced, not rewritten in place: every node of the run comes with its own start
    // request, and rewriting truncated the file under a node of the same run that was
    // reading it ("expected a scene": 1 run in 8 with 4-8 nodes per agent; performance.md).
    write_file(run.folder / "scene.yaml", request.value("scene_yaml", ""));
    transport::UnicastNetwork network{request.value("address", ""), request.value("peers", std::vector<std::string>{}),
                                      request.value("lease_s", 5.0)};
    // A cut the run is meant to survive must not make this agent stop its nodes either.
    run.heartbeat_timeout_s = std::max(opt_.heartbeat_timeout_s, config::fault_timings(request.value("partition_grace_s", 0.0)).agent_timeout);
    if (network.address.empty() || addresses_.count(network.address) == 0)
      return refuse("the request names address '" + network.address + "', which is not one of this host's");
    const std::vector<std::string> env = hostrun::write_unicast_dds_files((run.folder / "dds").string(), network);
    cosim::NodeCommandLine command_line{.scene = (run.folder / "scene.yaml").string(), .nodes = members, .run_id = m.run_id,
                                        .domain = opt_.domain, .run_dir = run.folder.string()};
    // The launcher's control writer: its nodes take commands from nobody else.
    if (const std::string guid = request.value("control_writer", ""); !guid.empty()) {
      if (guid.size() != 33 || guid[24] != ':' ||
          guid.find_first_not_of("0123456789abcdef:") != std::string::npos)
        return refuse("the request's control_writer '" + guid + "' is not a GUID (24 hex digits ':' 8 hex digits)");
      command_line.control_writer = guid;
    }
    run.processes.start(m.node, executable, command_line.to_arguments(), (run.folder / (m.node + ".log")).string(), env);
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
  log_line("run " + std::to_string(m.run_id) + ": started " + type + " '" + m.node + "' in " + run.folder.string());
  reply(m.run_id, AgentKind::started, m.node, json{{"pid", run.processes.processes().back().pid}}.dump());
}

void Agent::stream_logs(AgentRun& run) {
  for (const auto& p : run.processes.processes()) {
    const fs::path path = run.folder / (p.name + ".log");
    std::ifstream in(path, std::ios::binary);
    if (!in) continue;
    std::uint64_t& sent = run.log_sent[p.name];
    in.seekg(static_cast<std::streamoff>(sent));
    std::vector<char> buffer(transport::kAgentChunkBytes);
    for (;;) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const std::streamsize n = in.gcount();
      if (n <= 0) break;
      transport::AgentMessage m;
      m.run_id = run.run_id;
      m.kind = static_cast<std::int32_t>(AgentKind::log);
      m.node = p.name;
      const auto* bytes = reinterpret_cast<const std::byte*>(buffer.data());
      m.data.assign(bytes, bytes + n);
      send(std::move(m));
      sent += static_cast<std::uint64_t>(n);
    }
  }
}

void Agent::report_exits(AgentRun& run) {
  run.processes.poll();
  for (const auto& p : run.processes.processes()) {
    if (!p.exited || run.exit_reported.count(p.name)) continue;
    stream_logs(run);  // the last lines before the exit report
    reply(run.run_id, AgentKind::exited, p.name,
          json{{"exit_code", p.exit_code}, {"signalled", p.signalled}, {"signal", p.signal}, {"describe", p.describe_exit()}}.dump());
    log_line("run " + std::to_string(run.run_id) + ": node '" + p.name + "' " + p.describe_exit());
    run.exit_reported.insert(p.name);
  }
}

void Agent::stop_run(AgentRun& run, const std::string& why) {
  if (run.processes.all_exited()) return;
  log_line("run " + std::to_string(run.run_id) + ": stopping its nodes: " + why);
  run.processes.stop_all(2.0);
  report_exits(run);
}

void Agent::collect(AgentRun& run) {
  stop_run(run, "the launcher collects the files");
  report_exits(run);
  // Every file the nodes wrote, whole (the streamed log included: the file is the record).
  json names = json::array();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(run.folder, ec)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name == "scene.yaml") continue;  // the launcher's own
    const std::string bytes = read_file(entry.path());
    std::size_t offset = 0;
    do {
      const std::size_t n = std::min(transport::kAgentChunkBytes, bytes.size() - offset);
      transport::AgentMessage m;
      m.run_id = run.run_id;
      m.kind = static_cast<std::int32_t>(AgentKind::file);
      m.node = name;
      m.text = json{{"offset", offset}, {"size", bytes.size()}}.dump();
      const auto* p = reinterpret_cast<const std::byte*>(bytes.data() + offset);
      m.data.assign(p, p + n);
      send(std::move(m));
      offset += n;
    } while (offset < bytes.size());
    names.push_back(name);
  }
  reply(run.run_id, AgentKind::collected, "", json{{"files", names}}.dump());
  log_line("run " + std::to_string(run.run_id) + ": handed back " + std::to_string(names.size()) + " files");
  if (!opt_.keep_run_folders) fs::remove_all(run.folder, ec);
}

void Agent::handle(const transport::AgentMessage& m) {
  if (!meant_for_me(m.host) || m.run_id == 0) return;
  const auto kind = static_cast<AgentKind>(m.kind);
  if (finished_.count(m.run_id)) {
    // The launcher repeats a request until it hears the answer: say it again, do nothing.
    if (kind == AgentKind::collect) reply(m.run_id, AgentKind::collected, "", json{{"files", json::array()}, {"again", true}}.dump());
    return;
  }
  auto it = runs_.find(m.run_id);
  switch (kind) {
    case AgentKind::start:
      start_node(m);
      break;
    case AgentKind::heartbeat:
      if (it != runs_.end()) it->second->last_heartbeat = Clock::now();
      break;
    case AgentKind::stop:
      if (it != runs_.end()) stop_run(*it->second, "the launcher asked");
      break;
    case AgentKind::collect:
      if (it != runs_.end()) {
        collect(*it->second);
        runs_.erase(it);
      } else {
        reply(m.run_id, AgentKind::collected, "", json{{"files", json::array()}}.dump());
      }
      finished_.insert(m.run_id);
      break;
    default:
      break;
  }
}

// The work folder is this agent's alone: a second agent on it would overwrite the DDS
// configuration the first one's nodes read (their own address) and hand back, then remove,
// the first one's node files. An flock dies with the process, so a killed agent frees it.
void Agent::lock_work_dir() {
  fs::create_directories(opt_.work_dir);
  const fs::path lock = fs::path(opt_.work_dir) / "agent.lock";
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) throw std::runtime_error(lock.string() + ": cannot open: " + std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = read_file(lock);
    throw std::runtime_error("work folder " + opt_.work_dir + " is in use by another mechsim agent (" +
                             (holder.empty() ? std::string("see ") + lock.string() : holder) +
                             "): give each agent a folder of its own with --work-dir, or leave it out (default: one "
                             "folder per address and domain; docs/hosts.md)");
  }
  const std::string me = "pid " + std::to_string(::getpid()) + ", address " +
                         (opt_.address.empty() ? std::string("loopback") : opt_.address) + ", domain " + std::to_string(opt_.domain);
  if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size()))
    throw std::runtime_error(lock.string() + ": cannot write: " + std::strerror(errno));
}

int Agent::run() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  lock_work_dir();
  const auto local = hostrun::local_ipv4_addresses();
  if (!opt_.address.empty()) {
    if (std::find(local.begin(), local.end(), opt_.address) == local.end())
      throw std::runtime_error("--address " + opt_.address + " is not an address of this host (it has: " +
                               hostrun::join(local, ", ") + ")");
    addresses_.insert(opt_.address);
    transport::UnicastNetwork network{opt_.address, opt_.peers};
    network.peers.push_back(opt_.address);
    hostrun::set_environment(hostrun::write_unicast_dds_files((fs::path(opt_.work_dir) / "dds").string(), network));
  } else {
    addresses_.insert("127.0.0.1");
    hostrun::configure_dds_environment();
  }
  const std::string vendor = opt_.vendor.empty() ? config::default_dds_vendor() : opt_.vendor;
  participant_ = transport::create_participant(vendor, opt_.domain);
  replies_ = participant_->create_agent_writer(transport::kAgentReplyTopic);
  requests_ = participant_->create_agent_reader(transport::kAgentRequestTopic);
  log_line("serving domain " + std::to_string(opt_.domain) + " on " + hostrun::join({addresses_.begin(), addresses_.end()}, ", ") +
           " (" + vendor + "), work folder " + opt_.work_dir + ", heartbeat timeout " + std::to_string(opt_.heartbeat_timeout_s) + " s");
  const auto started = Clock::now();
  auto last_hello = Clock::now() - std::chrono::hours(1);
  auto last_logs = Clock::now();
  while (!g_stop) {
    if (opt_.exit_after_s > 0 && seconds_since(started) > opt_.exit_after_s) break;
    participant_->wait(std::chrono::milliseconds(50));
    while (auto m = requests_->take()) handle(*m);
    for (auto it = runs_.begin(); it != runs_.end();) {
      AgentRun& run = *it->second;
      report_exits(run);
      if (seconds_since(last_logs) > 0.2) stream_logs(run);
      if (seconds_since(run.last_heartbeat) > run.heartbeat_timeout_s) {
        stop_run(run, "no heartbeat from the launcher for " + std::to_string(run.heartbeat_timeout_s) + " s");
        log_line("run " + std::to_string(run.run_id) + ": forgotten; its files stay in " + run.folder.string());
        finished_.insert(run.run_id);
        it = runs_.erase(it);
        continue;
      }
      ++it;
    }
    if (seconds_since(last_logs) > 0.2) last_logs = Clock::now();
    if (seconds_since(last_hello) > kHelloPeriodS) {
      hello();
      last_hello = Clock::now();
    }
  }
  for (auto& [id, run] : runs_) stop_run(*run, g_stop ? "the agent is stopping" : "the agent's time is up");
  log_line("stopped");
  return 0;
}

}  // namespace

std::string default_work_dir(const std::string& address, int domain) {
  return std::string(kWorkDirRoot) + "/" + (address.empty() ? std::string("loopback") : address) + "-domain" + std::to_string(domain);
}

int run_agent(const AgentOptions& options) {
  try {
    Agent agent(options);
    return agent.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mechsim agent: %s\n", e.what());
    return 1;
  }
}

}  // namespace mechsim::agent
