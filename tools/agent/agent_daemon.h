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

// Where an agent keeps its files when --work-dir is not given: one folder per address and
// domain, /var/tmp/mechsim-agent/<address>-domain<D> ("loopback" without an address), so
// that agents sharing a filesystem (namespaces, containers with a shared volume, NFS) never
// write each other's DDS configuration or node files.
inline constexpr const char* kWorkDirRoot = "/var/tmp/mechsim-agent";
std::string default_work_dir(const std::string& address, int domain);

struct AgentOptions {
  int domain = 0;
  std::string work_dir;              // run folders of the nodes it starts ("" = default_work_dir())
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
