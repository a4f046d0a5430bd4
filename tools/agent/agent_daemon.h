// `mechsim agent` as a standing DDS daemon (docs/hosts.md, "The DDS agent"): a DDS
// participant on one domain that serves the launchers of that domain (agent_protocol.h,
// agent_service.h). It authenticates nobody: anyone who can reach its domain can start
// nodes, read and stop runs. So it serves loopback only, unless started with
// --allow-unauthenticated on a network the user trusts; across hosts the default is the
// SSH session (agent_stdio.h). Leaves nothing running when the launcher goes silent
// (heartbeat timeout) or the agent is stopped (SIGTERM, SIGINT).
#pragma once

#include <string>

#include "agent_service.h"

namespace mechsim::agent {

// Where an agent keeps its files when --work-dir is not given: one folder per address and
// domain, /var/tmp/mechsim-agent/<address>-domain<D> ("loopback" without an address), so
// that agents sharing a filesystem (namespaces, containers with a shared volume, NFS) never
// write each other's DDS configuration or node files.
inline constexpr const char* kWorkDirRoot = "/var/tmp/mechsim-agent";
std::string default_work_dir(const std::string& address, int domain);

// The refusal of a daemon on a non-loopback address without --allow-unauthenticated ("":
// allowed).
std::string unauthenticated_daemon_problem(const AgentOptions& options);

// Runs until SIGTERM/SIGINT (or exit_after_s). Returns the process exit code.
int run_agent(const AgentOptions& options);

}  // namespace mechsim::agent
