// `mechsim agent`: the daemon on each further host of a multi-host run (docs/hosts.md). A
// DDS participant on one domain that starts mechsim node executables when a launcher of
// that domain asks (agent_protocol.h), streams their logs, reports their exits, and hands
// the run folder's files back at the end. It starts nothing but the node types of the
// catalog, from its own build's bin folder, and leaves nothing running when the launcher
// goes silent (heartbeat timeout) or the agent is stopped (SIGTERM, SIGINT).
#pragma once

#include <string>
#include <vector>

namespace mechsim::agent {

struct AgentOptions {
  int domain = 0;
  std::string work_dir = "/var/tmp/mechsim-agent";  // run folders of the nodes it starts
  std::string address;               // this host's IPv4 address on the run network ("" = loopback only)
  std::vector<std::string> peers;    // addresses of the launchers' hosts (unicast discovery)
  std::string vendor;                // DDS vendor of the agent's own participant ("" = the default)
  double heartbeat_timeout_s = 5.0;  // launcher silent this long: its run's nodes are stopped
  bool keep_run_folders = false;     // keep the node files after handing them back
  double exit_after_s = 0.0;         // > 0: stop after this long (tests)
};

// Runs until SIGTERM/SIGINT (or exit_after_s). Returns the process exit code.
int run_agent(const AgentOptions& options);

}  // namespace mechsim::agent
