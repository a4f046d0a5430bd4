// `mechsim agent`: the per-host daemon of multi-host runs (tools/agent/agent_daemon.h, docs/hosts.md).
#include <memory>

#include "agent_daemon.h"
#include "commands.h"
#include "mechsim/transport/backends.h"

namespace mechsim::tools {

void add_agent_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("agent",
                                 "Serve this host in multi-host runs: start mechsim nodes when a launcher of the domain asks, "
                                 "stream their logs, report their exits, hand their files back (docs/hosts.md)");
  auto opt = std::make_shared<agent::AgentOptions>();
  auto peers = std::make_shared<std::string>();
  cmd->add_option("--domain", opt->domain, "DDS domain id the launchers of this host's runs use (the scenes' dds.domain)")
      ->required()
      ->check(CLI::Range(0, 232));
  cmd->add_option("--address", opt->address,
                  "this host's IPv4 address on the run network (omitted: loopback only, for trying it on one machine)");
  cmd->add_option("--peers", *peers, "comma-separated addresses of the launchers' hosts (unicast discovery, no multicast)");
  cmd->add_option("--work-dir", opt->work_dir,
                  std::string("folder for its DDS configuration and the run folders of the nodes it starts, this agent's "
                              "alone (default: ") + agent::kWorkDirRoot + "/<address>-domain<D>, 'loopback' without --address)");
  cmd->add_option("--dds", opt->vendor, "DDS vendor of the agent's own participant (default: the build's default)")
      ->check(CLI::IsMember(transport::available_vendors()));
  cmd->add_option("--heartbeat-timeout", opt->heartbeat_timeout_s,
                  "seconds without a launcher heartbeat after which a run's nodes are stopped")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--keep", opt->keep_run_folders, "keep the node files after handing them back");
  cmd->add_option("--exit-after", opt->exit_after_s, "stop after this many seconds (tests)");
  cmd->callback([opt, peers, &exit_code] {
    std::string rest = *peers;
    while (!rest.empty()) {
      const auto comma = rest.find(',');
      const std::string one = rest.substr(0, comma);
      if (!one.empty()) opt->peers.push_back(one);
      rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    }
    exit_code = agent::run_agent(*opt);
  });
}

}  // namespace mechsim::tools
