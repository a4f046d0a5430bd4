#include "agent_service.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "agent_protocol.h"
#include "atomic_file.h"
#include "elapsed.h"
#include "hosts.h"
#include "install_paths.h"
#include "mechsim/config/hash.h"
#include "mechsim/config/scene.h"
#include "mechsim/catalog/catalog.h"
#include "mechsim/cosim/node_command_line.h"
#include "mechsim/cosim/node_end_record.h"
#include "mechsim/transport/network_config.h"

namespace mechsim::agent {

namespace fs = std::filesystem;
using hostrun::AgentKind;
using hostrun::kAllAgents;
using hostrun::kGroupType;
using hostrun::kHelloPeriodS;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

void log_line(const std::string& text) {
  std::fprintf(stderr, "mechsim agent: %s\n", text.c_str());
  std::fflush(stderr);
}

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

namespace {

std::atomic<int> g_stop{0};
void on_stop_signal(int sig) { g_stop.store(sig); }

bool plain_name(const std::string& name) { return !name.empty() && name.find('/') == std::string::npos && name[0] != '.'; }

}  // namespace

void catch_stop_signals(bool hangup) {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  if (hangup) std::signal(SIGHUP, on_stop_signal);
  std::signal(SIGPIPE, SIG_IGN);
}

int stop_signal() { return g_stop.load(); }

// One run a launcher asked this agent to take part in.
struct AgentService::Run {
  std::uint64_t run_id = 0;
  fs::path folder;
  hostrun::NodeProcesses processes;
  std::map<std::string, std::uint64_t> log_sent;  // node -> bytes of its log already sent
  std::set<std::string> exit_reported;
  std::map<std::string, std::vector<std::string>> members;  // process -> the nodes it steps
  Clock::time_point last_heartbeat = Clock::now();
  double heartbeat_timeout_s = 5.0;
};

AgentService::AgentService(const AgentOptions& options, std::set<std::string> addresses, std::string transport, Send send)
    : opt_(options), addresses_(std::move(addresses)), transport_(std::move(transport)), send_(std::move(send)) {
  last_hello_ = Clock::now() - std::chrono::hours(1);
  last_logs_ = Clock::now();
}

AgentService::~AgentService() = default;

bool AgentService::meant_for_me(const std::string& host) const { return host == kAllAgents || addresses_.count(host) > 0; }

std::size_t AgentService::running_processes() const {
  std::size_t n = 0;
  for (const auto& [id, run] : runs_)
    for (const auto& p : run->processes.processes()) n += p.exited ? 0 : 1;
  return n;
}

void AgentService::reply(std::uint64_t run_id, std::int32_t kind, const std::string& node, const std::string& text) {
  transport::AgentMessage m;
  m.run_id = run_id;
  m.kind = kind;
  m.node = node;
  m.text = text;
  m.host = opt_.address.empty() ? "127.0.0.1" : opt_.address;
  m.sequence = ++sequence_;
  send_(std::move(m));
}

void AgentService::hello() {
  char hostname[256] = "";
  ::gethostname(hostname, sizeof hostname - 1);
  json j{{"addresses", json(std::vector<std::string>(addresses_.begin(), addresses_.end()))},
         {"hostname", hostname},
         {"pid", static_cast<long>(::getpid())},
         {"vendor", transport_},
         {"runs", runs_.size()}};
  reply(0, static_cast<std::int32_t>(AgentKind::hello), "", j.dump());
}

void AgentService::start_node(const transport::AgentMessage& m, const std::string& sender) {
  auto refuse = [&](const std::string& why) {
    log_line("refused node '" + m.node + "' of run " + std::to_string(m.run_id) + " from " + sender + ": " + why);
    reply(m.run_id, static_cast<std::int32_t>(AgentKind::refused), m.node, why);
  };
  if (auto it = runs_.find(m.run_id); it != runs_.end()) {
    it->second->last_heartbeat = Clock::now();
    for (const auto& p : it->second->processes.processes())
      if (p.name == m.node)  // a repeated request: it was started, say so again
        return reply(m.run_id, static_cast<std::int32_t>(AgentKind::started), m.node, json{{"pid", p.pid}}.dump());
  }
  // Bounds before anything is parsed or written (docs/hosts.md, "Bounds").
  if (m.text.size() > opt_.limits.max_file_bytes)
    return refuse("the start request of " + std::to_string(m.text.size()) + " bytes exceeds this host's --max-file-bytes " +
                  std::to_string(opt_.limits.max_file_bytes));
  if (running_processes() >= static_cast<std::size_t>(opt_.limits.max_processes))
    return refuse("this host runs " + std::to_string(running_processes()) + " node processes, its --max-processes " +
                  std::to_string(opt_.limits.max_processes));
  const json request = json::parse(m.text, nullptr, false);
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
  if (!plain_name(folder_name)) return refuse("run_folder must be a plain folder name, got '" + folder_name + "'");
  std::vector<std::string> names = members;
  names.push_back(m.node);
  for (const std::string& name : names)
    if (!plain_name(name)) return refuse("a participant (or process group) name must be a plain name, got '" + name + "'");
  if (request.value("domain", -1) != opt_.domain)
    return refuse("the request is for domain " + std::to_string(request.value("domain", -1)) + ", this agent serves " +
                  std::to_string(opt_.domain));
  std::string executable;
  try {
    executable = hostrun::node_executable(type);
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
  auto& slot = runs_[m.run_id];
  if (!slot) {
    slot = std::make_unique<Run>();
    slot->run_id = m.run_id;
    slot->heartbeat_timeout_s = opt_.heartbeat_timeout_s;
    slot->processes.set_file_size_limit(opt_.limits.max_file_bytes);
  }
  Run& run = *slot;
  run.last_heartbeat = Clock::now();
  try {
    run.folder = fs::path(opt_.work_dir) / folder_name;
    fs::create_directories(run.folder);
    // Replaced, not rewritten in place: every node of the run comes with its own start
    // request, and rewriting truncated the file under a node of the same run that was
    // reading it ("expected a scene": 1 run in 8 with 4-8 nodes per agent; performance.md).
    tools::write_file_atomically((run.folder / "scene.yaml").string(),
                                 with_received_files(request.value("scene_yaml", ""), request.value("files", json::object())));
    transport::UnicastNetwork network{request.value("address", ""), request.value("peers", std::vector<std::string>{}),
                                      request.value("lease_s", 5.0), request.value("participants_per_host", transport::kMaxParticipantsPerHost)};
    // A cut the run is meant to survive must not make this agent stop its nodes either.
    run.heartbeat_timeout_s =
        std::max(opt_.heartbeat_timeout_s, config::fault_timings(request.value("partition_grace_s", 0.0)).agent_timeout);
    if (network.address.empty() || addresses_.count(network.address) == 0)
      return refuse("the request names address '" + network.address + "', which is not one of this host's");
    const std::vector<std::string> env = hostrun::write_unicast_dds_files((run.folder / "dds").string(), network);
    cosim::NodeCommandLine command_line{.scene = (run.folder / "scene.yaml").string(), .nodes = members, .run_id = m.run_id,
                                        .domain = opt_.domain, .run_dir = run.folder.string()};
    // The launcher's control writer: its nodes take commands from nobody else.
    if (const std::string guid = request.value("control_writer", ""); !guid.empty()) {
      if (guid.size() != 33 || guid[24] != ':' || guid.find_first_not_of("0123456789abcdef:") != std::string::npos)
        return refuse("the request's control_writer '" + guid + "' is not a GUID (24 hex digits ':' 8 hex digits)");
      command_line.control_writer = guid;
    }
    run.processes.start(m.node, executable, command_line.to_arguments(), (run.folder / (m.node + ".log")).string(), env);
    run.members[m.node] = members;
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
  log_line("run " + std::to_string(m.run_id) + ": started " + type + " '" + m.node + "' in " + run.folder.string());
  reply(m.run_id, static_cast<std::int32_t>(AgentKind::started), m.node, json{{"pid", run.processes.processes().back().pid}}.dump());
}

// A file the launcher sends with the run (an FMU): kept in <work_dir>/files/<sha256>/<name>,
// written chunk by chunk, checked against its hash when whole.
void AgentService::put_file(const transport::AgentMessage& m, const std::string& sender) {
  const json header = json::parse(m.text, nullptr, false);
  auto refuse = [&](const std::string& why) {
    log_line("refused file '" + m.node + "' from " + sender + ": " + why);
    reply(m.run_id, static_cast<std::int32_t>(AgentKind::refused), m.node, why);
  };
  if (header.is_discarded() || !header.is_object()) return refuse("the file's header is not a JSON object");
  const std::string name = header.value("name", "");
  const std::uint64_t offset = header.value("offset", std::uint64_t{0}), size = header.value("size", std::uint64_t{0});
  if (m.node.size() != 64 || m.node.find_first_not_of("0123456789abcdef") != std::string::npos)
    return refuse("a file is named by its sha256 (64 hex digits)");
  if (!plain_name(name)) return refuse("a file name must be a plain name, got '" + name + "'");
  if (size > opt_.limits.max_file_bytes)
    return refuse("a file of " + std::to_string(size) + " bytes exceeds this host's --max-file-bytes " + std::to_string(opt_.limits.max_file_bytes));
  if (offset + m.data.size() > size) return refuse("a chunk beyond the file's size");
  const fs::path folder = fs::path(opt_.work_dir) / "files" / m.node;
  const fs::path part = folder / (name + ".part");
  try {
    fs::create_directories(folder);
    std::fstream out(part, offset == 0 ? (std::ios::out | std::ios::binary | std::ios::trunc) : (std::ios::in | std::ios::out | std::ios::binary));
    out.seekp(static_cast<std::streamoff>(offset));
    out.write(reinterpret_cast<const char*>(m.data.data()), static_cast<std::streamsize>(m.data.size()));
    if (!out) throw std::runtime_error(part.string() + ": cannot write");
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
  if (offset + m.data.size() < size) return;
  const std::string digest = config::sha256_hex(read_whole_file(part.string()));
  if (digest != m.node) {
    fs::remove(part);
    return refuse("'" + name + "' arrived with sha256 " + digest + ", not the " + m.node + " it was sent as");
  }
  fs::rename(part, folder / name);
  received_[m.node] = (folder / name).string();
  log_line("received '" + name + "' (" + std::to_string(size) + " bytes, sha256 " + m.node + ")");
  reply(m.run_id, static_cast<std::int32_t>(AgentKind::stored), m.node, name);
}

std::string AgentService::with_received_files(std::string scene, const json& files) const {
  if (!files.is_object()) return scene;
  for (const auto& [path, sha] : files.items()) {
    const auto copy = sha.is_string() ? received_.find(sha.get<std::string>()) : received_.end();
    if (copy == received_.end()) throw std::runtime_error("the scene's file " + path + " did not arrive (its sha256 checked) before the start");
    if (path.empty()) continue;
    for (std::size_t at = scene.find(path); at != std::string::npos; at = scene.find(path, at + copy->second.size()))
      scene.replace(at, path.size(), copy->second);
    log_line("the scene's " + path + " is " + copy->second);
  }
  return scene;
}

void AgentService::stream_logs(Run& run) {
  for (const auto& p : run.processes.processes()) {
    std::ifstream in(run.folder / (p.name + ".log"), std::ios::binary);
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
      m.host = opt_.address.empty() ? "127.0.0.1" : opt_.address;
      m.sequence = ++sequence_;
      const auto* bytes = reinterpret_cast<const std::byte*>(buffer.data());
      m.data.assign(bytes, bytes + n);
      send_(std::move(m));
      sent += static_cast<std::uint64_t>(n);
    }
  }
}

void AgentService::report_exits(Run& run) {
  run.processes.poll();
  for (const auto& p : run.processes.processes()) {
    if (!p.exited || run.exit_reported.count(p.name)) continue;
    stream_logs(run);  // the last lines before the exit report
    // Whether it wrote its end record (node_end_record.h): the record is on this host, and the
    // launcher tells a node that finished from one that exited 0 early by it.
    const auto& members = run.members[p.name];
    const bool reached_end = !members.empty() && std::all_of(members.begin(), members.end(), [&](const std::string& node) {
      return cosim::read_node_end_record(run.folder.string(), node).has_value();
    });
    reply(run.run_id, static_cast<std::int32_t>(AgentKind::exited), p.name,
          json{{"exit_code", p.exit_code}, {"signalled", p.signalled}, {"signal", p.signal}, {"describe", p.describe_exit()},
               {"reached_end", reached_end}}.dump());
    log_line("run " + std::to_string(run.run_id) + ": node '" + p.name + "' " + p.describe_exit());
    run.exit_reported.insert(p.name);
  }
}

void AgentService::stop_run(Run& run, const std::string& why) {
  if (run.processes.all_exited()) return;
  log_line("run " + std::to_string(run.run_id) + ": stopping its nodes: " + why);
  run.processes.stop_all(2.0);
  report_exits(run);
}

void AgentService::collect(Run& run) {
  stop_run(run, "the launcher collects the files");
  report_exits(run);
  // Every file the nodes wrote, whole (the streamed log included: the file is the record).
  json names = json::array();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(run.folder, ec)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name == "scene.yaml") continue;  // the launcher's own
    const std::string bytes = read_whole_file(entry.path().string());
    std::size_t offset = 0;
    do {
      const std::size_t n = std::min(transport::kAgentChunkBytes, bytes.size() - offset);
      transport::AgentMessage m;
      m.run_id = run.run_id;
      m.kind = static_cast<std::int32_t>(AgentKind::file);
      m.node = name;
      m.host = opt_.address.empty() ? "127.0.0.1" : opt_.address;
      m.sequence = ++sequence_;
      m.text = json{{"offset", offset}, {"size", bytes.size()}}.dump();
      const auto* p = reinterpret_cast<const std::byte*>(bytes.data() + offset);
      m.data.assign(p, p + n);
      send_(std::move(m));
      offset += n;
    } while (offset < bytes.size());
    names.push_back(name);
  }
  reply(run.run_id, static_cast<std::int32_t>(AgentKind::collected), "", json{{"files", names}}.dump());
  log_line("run " + std::to_string(run.run_id) + ": handed back " + std::to_string(names.size()) + " files");
  if (!opt_.keep_run_folders) fs::remove_all(run.folder, ec);
}

void AgentService::handle(const transport::AgentMessage& m, const std::string& sender) {
  if (!meant_for_me(m.host) || m.run_id == 0) return;
  const auto kind = static_cast<AgentKind>(m.kind);
  if (finished_.count(m.run_id)) {
    // The launcher repeats a request until it hears the answer: say it again, do nothing.
    if (kind == AgentKind::collect)
      reply(m.run_id, static_cast<std::int32_t>(AgentKind::collected), "", json{{"files", json::array()}, {"again", true}}.dump());
    return;
  }
  auto it = runs_.find(m.run_id);
  switch (kind) {
    case AgentKind::start:
      start_node(m, sender);
      break;
    case AgentKind::put_file:
      put_file(m, sender);
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
        reply(m.run_id, static_cast<std::int32_t>(AgentKind::collected), "", json{{"files", json::array()}}.dump());
      }
      finished_.insert(m.run_id);
      break;
    default:
      log_line("ignored a message of kind " + std::to_string(m.kind) + " from " + sender + ": not a request");
      break;
  }
}

void AgentService::tick() {
  const bool logs_due = seconds_since(last_logs_) > 0.2;
  for (auto it = runs_.begin(); it != runs_.end();) {
    Run& run = *it->second;
    report_exits(run);
    if (logs_due) stream_logs(run);
    if (seconds_since(run.last_heartbeat) > run.heartbeat_timeout_s) {
      stop_run(run, "no heartbeat from the launcher for " + std::to_string(run.heartbeat_timeout_s) + " s");
      log_line("run " + std::to_string(run.run_id) + ": forgotten; its files stay in " + run.folder.string());
      finished_.insert(run.run_id);
      it = runs_.erase(it);
      continue;
    }
    ++it;
  }
  if (logs_due) last_logs_ = Clock::now();
  if (seconds_since(last_hello_) > kHelloPeriodS) {
    hello();
    last_hello_ = Clock::now();
  }
}

void AgentService::stop_all(const std::string& why) {
  for (auto& [id, run] : runs_) stop_run(*run, why);
}

}  // namespace mechsim::agent
