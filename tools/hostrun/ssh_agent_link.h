// The launcher's SSH sessions to the agents of a run's hosts (docs/hosts.md): per host one
// `ssh [-F CONFIG] TARGET -- MECHSIM agent --stdio --domain D` child, its stdin and stdout a
// socket of this process carrying agent frames (agent_frame.h), its stderr (ssh's own
// messages and the agent's log lines) in <run>/ssh-<host>.log. OpenSSH does the trust: the
// user's keys and agent, ~/.ssh/config, known_hosts, BatchMode (no password prompt). The
// sessions end with this object (the remote agent sees stdin end and stops its nodes), and
// with this process (PR_SET_PDEATHSIG).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "agent_link.h"

namespace mechsim::hostrun {

struct SshSession {
  std::string address;            // the host's address on the run network: its replies' host
  std::vector<std::string> argv;  // ssh_agent_command()
  std::string log_path;           // ssh's stderr
};

// The command of one session. `ssh_command`: the ssh program and its options, split on
// spaces (the MECHSIM_SSH environment variable, default "ssh"); `ssh_config`: a file for
// -F ("" = ssh's own ~/.ssh/config); `target`: [user@]host; `remote_mechsim`: the mechsim
// executable on that host.
std::vector<std::string> ssh_agent_command(const std::string& ssh_command, const std::string& ssh_config, const std::string& target,
                                           const std::string& remote_mechsim, int domain);
// Starts every session (throws std::runtime_error naming what could not start).
std::unique_ptr<AgentLink> ssh_agent_link(const std::vector<SshSession>& sessions);

}  // namespace mechsim::hostrun
