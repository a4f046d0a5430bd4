// The conversation between a launcher and the `mechsim agent` of another host
// (docs/hosts.md), on mechsim/agent/request (launcher -> agents) and mechsim/agent/reply
// (agents -> launcher), both RELIABLE + KEEP_ALL + VOLATILE on the run's domain.
//
//   agent    -> hello      every second: its addresses and host name (text, JSON)
//   launcher -> start      one node: host = the agent's address, node = participant,
//                          text = {type, scene_yaml, run_folder, domain, address, peers};
//                          or a process group: node = "process-<group>", type =
//                          "node_group", members = [participants] (docs/scenes.md)
//   agent    -> started    node started (the launcher repeats `start` every second until
//                          this comes: a sample written right after discovery can be lost)
//   agent    -> refused    node (or "" for the whole request) not started: text = why
//   agent    -> log        node, data = the next bytes of its log
//   agent    -> exited     node, text = {exit_code, signalled, signal, describe}
//   launcher -> heartbeat  every 0.5 s while the run lives; an agent that hears none for its
//                          --heartbeat-timeout stops the run's nodes (the launcher is gone)
//   launcher -> stop       stop the run's nodes (SIGTERM, then SIGKILL after 2 s)
//   launcher -> collect    send the run folder's files, then forget the run (repeated
//                          until `collected`)
//   agent    -> file       node = file name, data = a chunk, text = {offset, size}
//   agent    -> collected  text = {files: [names]}: every chunk of every file was written
//   launcher -> put_file   a file a participant names (an FMU), before the start that needs
//                          it: node = its sha256 (hex), text = {name, offset, size}, data = a
//                          chunk; the agent checks the hash when the last chunk is in and
//                          answers `stored` (node = the hash) or `refused` (node = the hash)
//   launcher -> start ...  text.files = {path in the scene: sha256}: the agent points the
//                          scene's path at its checked copy, or refuses the start
//
// Every message carries the run id; an agent acts only on requests whose host is one of its
// own addresses (or "*", for all agents of the run).
#pragma once

#include <cstdint>

namespace mechsim::hostrun {

enum class AgentKind : std::int32_t {
  hello = 1,
  started = 2,
  refused = 3,
  log = 4,
  exited = 5,
  file = 6,
  collected = 7,
  stored = 8,
  start = 101,
  heartbeat = 102,
  stop = 103,
  collect = 104,
  put_file = 105,
};

inline constexpr const char* kAllAgents = "*";
// The `type` of a start request for a process group, and the executable that runs a group's
// nodes on one executor thread (nodes/common/node_group.cpp), on any host.
inline constexpr const char* kGroupType = "node_group";
inline constexpr double kHeartbeatPeriodS = 0.5;
inline constexpr double kDefaultHeartbeatTimeoutS = 5.0;
inline constexpr double kHelloPeriodS = 1.0;

}  // namespace mechsim::hostrun
