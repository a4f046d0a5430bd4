// What a mechsim agent does with a request (agent_protocol.h), whatever carried it: start a
// node, stop a run's nodes, hand back a run's files, note a heartbeat; and, between
// requests, stream logs, report exits and stop the nodes of a silent launcher. Both
// transports use it: the SSH session of `mechsim agent --stdio` (agent_stdio.h, the
// default across hosts) and the standing DDS daemon (agent_daemon.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "mechsim/transport/messages.h"
#include "node_processes.h"

namespace mechsim::agent {

// What one request can make this host do (docs/hosts.md, "Bounds").
struct AgentLimits {
  int max_processes = 64;                        // node processes running at once, all runs together
  std::uint64_t max_file_bytes = 1ull << 30;     // any one file a node writes (RLIMIT_FSIZE), and a request's scene text
};

struct AgentOptions {
  int domain = 0;
  std::string work_dir;              // run folders of the nodes it starts ("" = the transport's default)
  std::string address;               // DDS daemon: this host's IPv4 address on the run network ("" = loopback only)
  std::vector<std::string> peers;    // DDS daemon: addresses of the launchers' hosts (unicast discovery)
  std::string vendor;                // DDS daemon: vendor of the agent's own participant ("" = the default)
  double heartbeat_timeout_s = 5.0;  // launcher silent this long: its run's nodes are stopped
  bool keep_run_folders = false;     // keep the node files after handing them back
  double exit_after_s = 0.0;         // > 0: stop after this long (tests)
  bool allow_unauthenticated = false;  // DDS daemon on a non-loopback address (docs/hosts.md, threat model)
  AgentLimits limits;
};

void log_line(const std::string& text);
std::string read_whole_file(const std::string& path);
// SIGINT and SIGTERM (and SIGHUP with `hangup`) end the agent's loop: stop_signal() returns
// the signal that came (0: none). SIGPIPE is ignored (a closed reader is an error, not death).
void catch_stop_signals(bool hangup);
int stop_signal();

class AgentService {
 public:
  using Send = std::function<void(transport::AgentMessage)>;
  // `addresses`: this host's addresses a request may name; `transport`: said in the hello
  // ("ssh", or the DDS vendor of the daemon's participant).
  AgentService(const AgentOptions& options, std::set<std::string> addresses, std::string transport, Send send);
  ~AgentService();
  // One request; `sender` names where it came from, for the log lines of refusals.
  void handle(const transport::AgentMessage& m, const std::string& sender);
  // Exits, logs, heartbeat timeouts and the hello: call it every few tens of milliseconds.
  void tick();
  void stop_all(const std::string& why);
  // Whether `host` (a request's host field) names this agent.
  bool meant_for_me(const std::string& host) const;
  std::size_t running_processes() const;

 private:
  struct Run;
  void reply(std::uint64_t run_id, std::int32_t kind, const std::string& node, const std::string& text);
  void start_node(const transport::AgentMessage& m, const std::string& sender);
  void put_file(const transport::AgentMessage& m, const std::string& sender);
  // The scene text with each path of `files` ({path: sha256}) replaced by this agent's
  // checked copy; throws std::runtime_error naming a file that did not arrive whole.
  std::string with_received_files(std::string scene, const nlohmann::json& files) const;
  void stream_logs(Run& run);
  void report_exits(Run& run);
  void collect(Run& run);
  void stop_run(Run& run, const std::string& why);
  void hello();

  AgentOptions opt_;
  std::set<std::string> addresses_;
  std::string transport_;
  Send send_;
  std::map<std::uint64_t, std::unique_ptr<Run>> runs_;
  std::map<std::string, std::string> received_;  // sha256 -> the checked copy's path (<work_dir>/files/<sha256>/<name>)
  std::set<std::uint64_t> finished_;  // collected: requests for them are answered, not acted on
  std::uint64_t sequence_ = 0;
  std::chrono::steady_clock::time_point last_hello_{}, last_logs_{};
};

}  // namespace mechsim::agent
