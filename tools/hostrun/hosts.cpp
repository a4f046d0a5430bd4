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
  return layout;
}

}  // namespace mechsim::hostrun
