#include "hosts.h"

#include "atomic_file.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netdb.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "mechsim/config/config_node.h"

namespace mechsim::hostrun {

std::vector<std::string> local_ipv4_addresses() {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;
  for (ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_addr->sa_family != AF_INET || !(a->ifa_flags & IFF_UP)) continue;
    char text[INET_ADDRSTRLEN];
    const auto* in = reinterpret_cast<const sockaddr_in*>(a->ifa_addr);
    if (::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text)) out.emplace_back(text);
  }
  ::freeifaddrs(list);
  return out;
}

std::string resolve_ipv4(const std::string& address_or_name) {
  in_addr parsed{};
  if (::inet_pton(AF_INET, address_or_name.c_str(), &parsed) == 1) return address_or_name;
  addrinfo hints{};
  hints.ai_family = AF_INET;
  addrinfo* found = nullptr;
  const int rc = ::getaddrinfo(address_or_name.c_str(), nullptr, &hints, &found);
  if (rc != 0 || found == nullptr) throw std::runtime_error(std::string("does not resolve to an IPv4 address: ") + gai_strerror(rc));
  char text[INET_ADDRSTRLEN];
  ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr, text, sizeof text);
  ::freeaddrinfo(found);
  return text;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : separator) + i;
  return out;
}

std::vector<std::string> write_unicast_dds_files(const std::string& dir, const transport::UnicastNetwork& network) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::absolute(dir);
  fs::create_directories(folder);
  // Atomically: an agent writes them again for each node it starts in the run's folder while
  // the nodes started before may be reading them (16 stations on a host showed it).
  auto write = [](const fs::path& path, const std::string& text) {
    tools::write_file_atomically(path.string(), text);
    return path.string();
  };
  return {"CYCLONEDDS_URI=file://" + write(folder / "cyclonedds.xml", transport::cyclone_unicast_config(network)),
          "FASTRTPS_DEFAULT_PROFILES_FILE=" + write(folder / "fastdds.xml", transport::fastdds_unicast_profile(network))};
}

void set_environment(const std::vector<std::string>& entries) {
  for (const std::string& e : entries) {
    const auto eq = e.find('=');
    ::setenv(e.substr(0, eq).c_str(), e.substr(eq + 1).c_str(), 1);
  }
}

int participants_per_host(const config::Scene& scene, const std::string& launcher_host) {
  std::map<std::string, int> on_host;
  for (const auto& p : scene.participants) ++on_host[p.host.empty() ? launcher_host : p.host];
  int most = 0;
  for (const auto& [host, n] : on_host) most = std::max(most, n);
  // The launcher's participant, its recorder, its domain reader and a spare (a user's tool).
  constexpr int kBesideTheNodes = 4;
  return std::max(most + kBesideTheNodes, transport::kMaxParticipantsPerHost);
}

std::vector<std::string> files_of(const config::Scene& scene, const std::vector<std::string>& members) {
  std::vector<std::string> out;
  for (const std::string& name : members) {
    const config::ParticipantSpec* p = scene.find_participant(name);
    if (p == nullptr) continue;
    // `fmu: FILE` beside a type fmu's settings, or the map `fmu: {file, ...}` (mechsim/config/scene.h).
    const std::optional<config::ConfigNode> fmu = p->fmu ? p->fmu : p->fmu_participant ? std::optional(p->fmu_participant->child("fmu")) : std::nullopt;
    if (!fmu) continue;
    const std::string file = fmu->is_map() ? fmu->child("file").as_string() : fmu->as_string();
    if (std::find(out.begin(), out.end(), file) == out.end()) out.push_back(file);
  }
  return out;
}

HostLayout plan_hosts(const config::Scene& scene) {
  HostLayout layout;
  const auto local = local_ipv4_addresses();
  for (const auto& h : scene.hosts) {
    std::string address;
    try {
      address = resolve_ipv4(h.address);
    } catch (const std::exception& e) {
      throw config::ConfigError(scene.file, h.key_path + ".address", "expected an address this machine can reach: '" + h.address + "' " + e.what());
    }
    layout.address[h.name] = address;
    if (std::find(local.begin(), local.end(), address) != local.end()) {
      if (!layout.launcher_host.empty())
        throw config::ConfigError(scene.file, h.key_path + ".address", "expected one host per machine: hosts." + layout.launcher_host +
                                                                            " is this machine too");
      layout.launcher_host = h.name;
      layout.launcher_address = address;
    }
  }
  for (const auto& p : scene.participants)
    if (!p.host.empty() && p.host != layout.launcher_host) layout.remote[p.name] = layout.address.at(p.host);
  layout.multi_host = !layout.remote.empty();
  if (!layout.multi_host) return layout;
  if (layout.launcher_host.empty()) {
    std::string hosts;
    for (const auto& [name, address] : layout.address) hosts += (hosts.empty() ? "" : ", ") + name + " = " + address;
    throw config::ConfigError(scene.file, "hosts", "expected this machine among the hosts (it runs the launcher and the participants "
                                                   "without a host), but none of its addresses (" + join(local, ", ") +
                                                   ") is one of them: " + hosts);
  }
  layout.peers.push_back(layout.launcher_address);
  for (const auto& [participant, address] : layout.remote)
    if (std::find(layout.peers.begin(), layout.peers.end(), address) == layout.peers.end()) layout.peers.push_back(address);
  // One way to reach the agents of a run: SSH sessions, or the DDS daemons of its domain.
  for (const auto& h : scene.hosts)
    if (h.name != layout.launcher_host && std::count(layout.peers.begin(), layout.peers.end(), layout.address.at(h.name)))
      layout.remote_hosts[layout.address.at(h.name)] = h;
  const std::string control = layout.remote_hosts.begin()->second.control;
  for (const auto& [address, h] : layout.remote_hosts)
    if (h.control != control)
      throw config::ConfigError(scene.file, h.key_path + ".control", "expected every host of a run reached the same way: " +
                                                                          layout.remote_hosts.begin()->second.key_path + " has control " +
                                                                          control + ", this one " + h.control);
  layout.over_ssh = control == "ssh";
  layout.participants_per_host = participants_per_host(scene, layout.launcher_host);
  if (layout.participants_per_host > transport::kMostParticipantsPerHost)
    throw config::ConfigError(scene.file, "hosts", "expected at most " + std::to_string(transport::kMostParticipantsPerHost - 4) +
                                                       " participants on one host (a DDS domain has ports for " +
                                                       std::to_string(transport::kMostParticipantsPerHost) +
                                                       " participants per host): group them into processes (processes: per_core) or "
                                                       "spread them over more hosts");
  return layout;
}

}  // namespace mechsim::hostrun
