// Where the participants of a scene run (docs/hosts.md): the scene's `hosts:` resolved to
// IPv4 addresses, the launcher's own host found among them by this machine's addresses,
// and each participant either local (the launcher starts it) or on another host (that
// host's `mechsim agent` starts it).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/transport/network_config.h"

namespace mechsim::hostrun {

// This machine's IPv4 addresses (up interfaces, loopback included).
std::vector<std::string> local_ipv4_addresses();
// An IPv4 address as it is, or a host name resolved (getaddrinfo); throws std::runtime_error.
std::string resolve_ipv4(const std::string& address_or_name);
std::string join(const std::vector<std::string>& items, const std::string& separator);

struct HostLayout {
  bool multi_host = false;        // some participant runs on another host than the launcher
  std::string launcher_host;      // the scene's name of this machine ("" when it has none)
  std::string launcher_address;
  std::map<std::string, std::string> address;  // host name -> IPv4 address
  std::vector<std::string> peers;              // addresses of the launcher's host and every host in use
  std::map<std::string, std::string> remote;   // participant -> address of its host's agent (absent: local)
  std::map<std::string, config::HostSpec> remote_hosts;  // address -> the host an agent serves there
  bool over_ssh = true;                        // the agents are SSH sessions (false: standing DDS daemons)
  // DDS participants each host may hold (transport::UnicastNetwork): the most on one host,
  // and room for the launcher's own, at least the default 24.
  int participants_per_host = transport::kMaxParticipantsPerHost;
};

// Writes <dir>/cyclonedds.xml and <dir>/fastdds.xml for `network` (the folder is created)
// and returns the environment entries that point both vendors at them, absolute paths:
// {"CYCLONEDDS_URI=file://...", "FASTRTPS_DEFAULT_PROFILES_FILE=..."}. For the launcher's own
// process, an agent's own process and the nodes an agent starts. Throws std::runtime_error
// naming a file it cannot write.
std::vector<std::string> write_unicast_dds_files(const std::string& dir, const transport::UnicastNetwork& network);
// Sets "NAME=value" entries in this process's environment (before any DDS participant exists).
void set_environment(const std::vector<std::string>& entries);

// The participant indices every host of the run allows (HostLayout::participants_per_host):
// the most participants on one host plus the launcher's own, at least the default 24.
int participants_per_host(const config::Scene& scene, const std::string& launcher_host);

// The files the participants `members` name that a host must have: their FMUs (absolute, as
// the scene was written back), which travel with the run (AgentClient::send_files).
std::vector<std::string> files_of(const config::Scene& scene, const std::vector<std::string>& members);

// Throws config::ConfigError (file, key, what was expected) for a host that does not
// resolve, or when participants sit on other hosts and this machine is none of the hosts.
HostLayout plan_hosts(const config::Scene& scene);

}  // namespace mechsim::hostrun
