// Where participants run (tools/hostrun/hosts.h) and the generated unicast DDS
// configurations (transport/network_config.h) of multi-host runs (docs/hosts.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hosts.h"
#include "mechsim/transport/network_config.h"

namespace mechsim::hostrun {
namespace {

namespace fs = std::filesystem;

config::Scene scene_with_hosts(const std::string& hosts, const std::string& follower_host) {
  std::ifstream in(std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/cam_press.yaml");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  text.replace(text.find("mode: lockstep"), 14, "mode: lockstep\ndds: {domain: 17}\nhosts:\n" + hosts);
  if (!follower_host.empty()) text.replace(text.find("    type: follower"), 18, "    type: follower\n    host: " + follower_host);
  const fs::path path = fs::temp_directory_path() / ("mechsim-hosts-layout-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  return config::load_scene(path.string());
}

TEST(HostLayout, TheLauncherFindsItsOwnHostAndTheRemoteParticipants) {
  const HostLayout layout = plan_hosts(scene_with_hosts("  here: {address: 127.0.0.1}\n  far: {address: 10.255.255.1}\n", "far"));
  EXPECT_TRUE(layout.multi_host);
  EXPECT_EQ(layout.launcher_host, "here");
  EXPECT_EQ(layout.launcher_address, "127.0.0.1");
  ASSERT_EQ(layout.remote.size(), 1u);
  EXPECT_EQ(layout.remote.at("follower"), "10.255.255.1");
  EXPECT_EQ(layout.peers, (std::vector<std::string>{"127.0.0.1", "10.255.255.1"}));
}

// Over ssh by default; the ssh keys are carried as written (ssh_config made absolute), and a
// `[user@]host` that could be read as an ssh option is refused naming the key.
TEST(HostLayout, RemoteHostsAreReachedOverSshByDefault) {
  const HostLayout layout = plan_hosts(scene_with_hosts(
      "  here: {address: 127.0.0.1}\n  far: {address: 10.255.255.1, ssh: op@rtbox, ssh_config: /etc/mechsim/ssh_config}\n", "far"));
  EXPECT_TRUE(layout.over_ssh);
  ASSERT_EQ(layout.remote_hosts.count("10.255.255.1"), 1u);
  EXPECT_EQ(layout.remote_hosts.at("10.255.255.1").ssh, "op@rtbox");
  EXPECT_EQ(layout.remote_hosts.at("10.255.255.1").ssh_config, "/etc/mechsim/ssh_config");
  EXPECT_EQ(layout.participants_per_host, transport::kMaxParticipantsPerHost);  // 2 participants: the default 24
  const HostLayout daemon = plan_hosts(scene_with_hosts("  here: {address: 127.0.0.1}\n  far: {address: 10.255.255.1, control: dds_agent}\n", "far"));
  EXPECT_FALSE(daemon.over_ssh);
  for (const std::string target : {"-oProxyCommand=sh", "op@-x", "op@rt box", "@rtbox"}) {
    try {
      scene_with_hosts("  here: {address: 127.0.0.1}\n  far: {address: 10.255.255.1, ssh: '" + target + "'}\n", "far");
      FAIL() << "accepted ssh target '" << target << "'";
    } catch (const config::ConfigError& e) {
      EXPECT_EQ(e.key_path(), "hosts.far.ssh") << target;
    }
  }
}

// The participant indices of a run: the most participants on one host plus 4, at least 24.
TEST(HostLayout, ParticipantsPerHostFollowTheMostOnOneHost) {
  config::Scene scene;
  for (int i = 0; i < 28; ++i) scene.participants.push_back({.name = "p" + std::to_string(i), .type = "follower", .host = "b"});
  for (int i = 0; i < 5; ++i) scene.participants.push_back({.name = "q" + std::to_string(i), .type = "follower"});
  EXPECT_EQ(participants_per_host(scene, "a"), 32);
  scene.participants.resize(10);
  EXPECT_EQ(participants_per_host(scene, "a"), 24);
  const transport::UnicastNetwork network{"10.0.0.1", {"10.0.0.1", "10.0.0.2"}, 5.0, 32};
  EXPECT_NE(transport::cyclone_unicast_config(network).find("<MaxAutoParticipantIndex>31</MaxAutoParticipantIndex>"), std::string::npos);
  EXPECT_NE(transport::fastdds_unicast_profile(network).find("<maxInitialPeersRange>32</maxInitialPeersRange>"), std::string::npos);
}

TEST(HostLayout, ParticipantsOnTheLaunchersHostMakeASingleHostRun) {
  const HostLayout layout = plan_hosts(scene_with_hosts("  here: {address: localhost}\n", "here"));
  EXPECT_FALSE(layout.multi_host);
  EXPECT_EQ(layout.launcher_address, "127.0.0.1");  // a host name, resolved
  EXPECT_TRUE(layout.remote.empty());
}

TEST(HostLayout, AMachineThatIsNoneOfTheHostsIsRefusedWithItsAddresses) {
  try {
    plan_hosts(scene_with_hosts("  far: {address: 10.255.255.1}\n", "far"));
    FAIL() << "accepted a launcher on none of the hosts";
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key_path(), "hosts");
    EXPECT_NE(what.find("127.0.0.1"), std::string::npos) << what;  // this machine's addresses
    EXPECT_NE(what.find("far = 10.255.255.1"), std::string::npos) << what;
  }
}

TEST(HostLayout, AnUnresolvableHostNameNamesItsKey) {
  try {
    plan_hosts(scene_with_hosts("  here: {address: 127.0.0.1}\n  far: {address: no-such-host.invalid}\n", "far"));
    FAIL() << "accepted a host that does not resolve";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.key_path(), "hosts.far.address");
  }
}

TEST(NetworkConfig, CycloneUsesOneInterfaceUnicastPeersAndNoMulticast) {
  const std::string xml = transport::cyclone_unicast_config({"10.77.0.2", {"10.77.0.1", "10.77.0.2"}});
  EXPECT_NE(xml.find("<NetworkInterface address=\"10.77.0.2\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
  EXPECT_NE(xml.find("<Peer address=\"10.77.0.1\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<ParticipantIndex>auto</ParticipantIndex>"), std::string::npos);
  EXPECT_NE(xml.find("<MaxAutoParticipantIndex>23</MaxAutoParticipantIndex>"), std::string::npos);
}

TEST(NetworkConfig, FastDdsUsesUdpOnOneInterfaceWithInitialPeers) {
  const std::string xml = transport::fastdds_unicast_profile({"10.77.0.2", {"10.77.0.1", "10.77.0.3"}});
  EXPECT_NE(xml.find("<interfaceWhiteList>\n          <address>10.77.0.2</address>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<useBuiltinTransports>false</useBuiltinTransports>"), std::string::npos);
  EXPECT_NE(xml.find("<address>10.77.0.3</address>"), std::string::npos);
  EXPECT_EQ(xml.find("SHM"), std::string::npos);
  EXPECT_EQ(xml.find("239.255"), std::string::npos);  // no multicast locator
}

TEST(NetworkConfig, PortsToOpenFollowTheRtpsWellKnownPorts) {
  // 7400 + 250 d + 10 + 2 i and + 11 + 2 i, i = 0..23: for domain 17, 11660..11707.
  EXPECT_EQ(transport::rtps_unicast_port_range(17), "11660-11707");
  EXPECT_EQ(transport::rtps_unicast_port_range(0, 1), "7410-7411");
}

}  // namespace
}  // namespace mechsim::hostrun
