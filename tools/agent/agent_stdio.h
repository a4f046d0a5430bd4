// `mechsim agent --stdio`: the agent of one launcher's session, the default across hosts
// (docs/hosts.md). The launcher starts it over SSH (`ssh HOST mechsim agent --stdio
// --domain D`), so OpenSSH has authenticated the user with the user's keys and checked the
// host against known_hosts; the agent reads requests on stdin and writes replies on stdout
// (agent_frame.h) and serves nobody else: no socket, no DDS participant of its own. Its
// nodes and their files live in a folder of this session (mode 0700), and die with it:
// stdin's end (the launcher or its SSH session gone), SIGHUP, SIGTERM or SIGINT stop them.
// A malformed or oversized frame ends the session, with a log line naming the SSH client.
#pragma once

#include <string>

#include "agent_service.h"

namespace mechsim::agent {

// The session's folder when --work-dir is not given: /var/tmp/mechsim-agent-<uid>/ssh-<pid>.
std::string session_work_dir();

// Serves stdin/stdout until stdin ends or a signal comes. Returns the process exit code.
int run_stdio_agent(const AgentOptions& options);

}  // namespace mechsim::agent
