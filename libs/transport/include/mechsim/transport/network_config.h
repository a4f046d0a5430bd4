// The DDS network configuration of a multi-host run (docs/hosts.md), for both vendors,
// generated from the scene's hosts: each participant uses its host's one interface and
// finds the others by unicast to every host's address (initial peers), with multicast off,
// since many plant networks block it. Single-host runs keep the loopback files of
// config/dds/. Pure text generation: the launcher writes these files for its own host and
// an agent for the node processes it starts (tools/hostrun/hosts.h, tools/agent/).
#pragma once

#include <string>
#include <vector>

namespace mechsim::transport {

// The default number of DDS participants on one host of a multi-host run; unicast discovery
// reaches the well-known ports of participant indices 0..n-1 on each peer. A run with more
// on a host says so (UnicastNetwork::participants_per_host), up to kMostParticipantsPerHost:
// index 119's data port is the last of a domain's 250 (7400 + 250 d + 11 + 2 i).
inline constexpr int kMaxParticipantsPerHost = 24;
inline constexpr int kMostParticipantsPerHost = 120;

struct UnicastNetwork {
  std::string address;              // this host's IPv4 address on the run's network
  std::vector<std::string> peers;   // every host's IPv4 address (this one may be among them)
  // How long a silent participant counts as alive: longer than a cut the run should
  // survive (faults.partition_grace), or its endpoints are dropped and what was written in
  // the meantime is lost for good.
  double lease_s = 5.0;
  // DDS participants one host may hold (participant indices 0..n-1; the same on every host
  // of a run, since each probes that many ports on its peers): hostrun::participants_per_host.
  int participants_per_host = kMaxParticipantsPerHost;
};


// A CYCLONEDDS_URI document: <Interfaces><NetworkInterface address=.../>, AllowMulticast
// false, ParticipantIndex auto, Peers, the lease, fast repair of lost samples.
std::string cyclone_unicast_config(const UnicastNetwork& network);

// A FASTRTPS_DEFAULT_PROFILES_FILE document: UDPv4 restricted to the address, built-in
// transports off (no shared memory: two hosts of the namespace test bed share /dev/shm),
// initial peers = every host, no multicast locators, data sharing off.
std::string fastdds_unicast_profile(const UnicastNetwork& network);

// The UDP ports a host of a multi-host run on `domain_id` must let in (RTPS well-known
// ports: discovery and user traffic, unicast, for participant indices 0..n-1):
// 7400 + 250 d + 10 + 2 i and 7400 + 250 d + 11 + 2 i. Returned as "first-last".
std::string rtps_unicast_port_range(int domain_id, int participants = kMaxParticipantsPerHost);

}  // namespace mechsim::transport
