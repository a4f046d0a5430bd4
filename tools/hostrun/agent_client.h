// The launcher's side of the agent conversation (tools/hostrun/agent_protocol.h): finds the
// agents of the hosts a run needs, asks them to start nodes, keeps the run alive with
// heartbeats, writes the logs they stream into the run folder, and at the end collects
// the files the remote nodes wrote, so that the run folder holds what a single-host run's
// holds. NodeProcesses uses it for the participants placed on other hosts.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "agent_link.h"

namespace mechsim::hostrun {

struct RemoteExit {
  std::string node;
  int exit_code = 0;
  bool signalled = false;
  int signal = 0;
  std::string describe;  // "exit code 0 on 10.77.0.2", "refused by the agent on ...: why"
  bool reached_end = false;  // the node wrote its end record on its host (node_end_record.h)
};

class AgentClient {
 public:
  // `link`: the SSH sessions or the DDS daemons of the run's hosts (agent_link.h).
  AgentClient(std::unique_ptr<AgentLink> link, std::uint64_t run_id, std::string run_dir);
  ~AgentClient();
  // Waits until an agent answered from each address and the request writer reached them
  // all. Returns the addresses still without an agent at the timeout (empty: all there).
  std::vector<std::string> wait_for_agents(const std::vector<std::string>& addresses, double timeout_s,
                                           const std::function<bool()>& interrupted);
  // Asks the agent at `address` to start participant `node`; `request` is the start text (JSON).
  void start(const std::string& node, const std::string& address, const std::string& request);
  // Sends the files at `paths` (FMUs a participant names) to the agent at `address`, checked
  // there by hash (agent_protocol.h, put_file). Returns {path: sha256}, for the start's "files".
  std::map<std::string, std::string> send_files(const std::string& address, const std::vector<std::string>& paths);
  // Takes the replies (logs into <run_dir>/<node>.log), repeats unanswered starts, sends the
  // heartbeat when due. Cheap: call it from every wait loop of the launcher.
  void pump();
  std::vector<RemoteExit> take_exits();
  // Asks every agent to stop this run's nodes (SIGTERM, then SIGKILL).
  void stop_all();
  // Asks every agent for the files its nodes wrote and writes them into the run folder.
  // Returns a line per agent that did not hand back in time (empty: all files are here).
  // An agent silent for kSilentAgentS (it says hello every second: the network to its host
  // is cut, or the host is down) is not waited for beyond that.
  std::vector<std::string> collect(double timeout_s);
  static constexpr double kSilentAgentS = 3.0;
  // The agents' hello texts (JSON) by address, for the summary.
  const std::map<std::string, std::string>& agents() const { return hello_; }
  // Why the agent at `address` does not answer, when the link knows ("" otherwise).
  std::string problem(const std::string& address) const { return link_->problem(address); }

 private:
  void send(std::int32_t kind, const std::string& host, const std::string& node, const std::string& text);
  void handle(const transport::AgentMessage& m);

  std::unique_ptr<AgentLink> link_;
  std::uint64_t run_id_;
  std::string run_dir_;
  std::map<std::string, std::string> hello_;  // address -> hello text
  std::map<std::string, std::chrono::steady_clock::time_point> last_heard_;  // address -> last message
  struct PendingStart {
    std::string address, request;
    std::chrono::steady_clock::time_point sent;
  };
  std::map<std::string, PendingStart> pending_;  // node -> start not yet answered
  std::map<std::string, std::string> node_address_;
  std::vector<RemoteExit> exits_;
  std::set<std::string> collected_;  // addresses that handed back everything
  std::chrono::steady_clock::time_point last_heartbeat_{};
  std::uint64_t sequence_ = 0;
  bool stopped_ = false;
};

}  // namespace mechsim::hostrun
