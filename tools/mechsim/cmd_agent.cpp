// `mechsim agent`: a host's end of multi-host runs (docs/hosts.md): the SSH session's agent
// (--stdio, tools/agent/agent_stdio.h) or the standing DDS daemon (tools/agent/agent_daemon.h).
#include <memory>

#include "agent_daemon.h"
#include "agent_stdio.h"
#include "commands.h"
#include "mechsim/transport/backends.h"

namespace mechsim::tools {

void add_agent_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("agent",
                                 "Serve this host in multi-host runs: start mechsim nodes a launcher asks for, stream their "
                                 "logs, report their exits, hand their files back. --stdio: one launcher's SSH session (the "
                                 "default across hosts); without it a standing DDS daemon, loopback only unless "
                                 "--allow-unauthenticated (docs/hosts.md)");
  auto opt = std::make_shared<agent::AgentOptions>();
  auto peers = std::make_shared<std::string>();
  auto stdio = std::make_shared<bool>(false);
  cmd->add_flag("--stdio", *stdio,
                "serve the launcher on stdin/stdout (started by the launcher over ssh: `ssh HOST mechsim agent --stdio "
                "--domain D`); the nodes die with the session");
  cmd->add_option("--domain", opt->domain, "DDS domain id of the runs it serves (the scenes' dds.domain)")
      ->required()
      ->check(CLI::Range(0, 232));
  cmd->add_option("--address", opt->address,
                  "daemon: this host's IPv4 address on the run network (omitted: loopback only, for trying it on one machine)");
  cmd->add_option("--peers", *peers, "daemon: comma-separated addresses of the launchers' hosts (unicast discovery, no multicast)");
  cmd->add_flag("--allow-unauthenticated", opt->allow_unauthenticated,
                "daemon: serve a non-loopback --address although the DDS agent authenticates nobody: anyone on that network "
                "can start nodes here, read and stop runs (docs/hosts.md, 'Threat model')");
  cmd->add_option("--work-dir", opt->work_dir,
                  std::string("folder for the run folders of the nodes it starts, this agent's alone (default: --stdio ") +
                      "/var/tmp/mechsim-agent-<uid>/ssh-<pid>, removed at the session's end; daemon " + agent::kWorkDirRoot +
                      "/<address>-domain<D>, 'loopback' without --address)");
  cmd->add_option("--dds", opt->vendor, "daemon: DDS vendor of the agent's own participant (default: the build's default)")
      ->check(CLI::IsMember(transport::available_vendors()));
  cmd->add_option("--heartbeat-timeout", opt->heartbeat_timeout_s,
                  "seconds without a launcher heartbeat after which a run's nodes are stopped")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-processes", opt->limits.max_processes, "node processes this host runs at once; a start beyond is refused")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-file-bytes", opt->limits.max_file_bytes,
                  "bytes of any one file a node writes (RLIMIT_FSIZE: a node writing more is killed, SIGXFSZ) and of a "
                  "request's scene")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--keep", opt->keep_run_folders, "keep the node files after handing them back");
  cmd->add_option("--exit-after", opt->exit_after_s, "stop after this many seconds (tests)");
  cmd->callback([opt, peers, stdio, &exit_code] {
    std::string rest = *peers;
    while (!rest.empty()) {
      const auto comma = rest.find(',');
      const std::string one = rest.substr(0, comma);
      if (!one.empty()) opt->peers.push_back(one);
      rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    }
    exit_code = *stdio ? agent::run_stdio_agent(*opt) : agent::run_agent(*opt);
  });
}

}  // namespace mechsim::tools
