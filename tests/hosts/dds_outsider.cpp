// An outsider on a run's network (issue 37): a plain DDS participant with no part in the run,
// on its domain, that writes the requests the standing agent takes (agent_protocol.h: start a
// node of its own, stop and collect the run) for a run id it knows, to every host and to "*",
// for a while, and counts what answers. Prints {"requests": N, "replies": R, "matched_readers": M}.
//   dds_outsider DOMAIN OWN_ADDRESS PEER,PEER,... RUN_ID_HEX SECONDS WORK_DIR
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "agent_protocol.h"
#include "hosts.h"
#include "mechsim/transport/backends.h"

int main(int argc, char** argv) {
  using namespace mechsim;
  if (argc != 7) {
    std::fprintf(stderr, "usage: dds_outsider DOMAIN OWN_ADDRESS PEER,PEER,... RUN_ID_HEX SECONDS WORK_DIR\n");
    return 2;
  }
  const int domain = std::atoi(argv[1]);
  const std::string own = argv[2];
  std::vector<std::string> peers;
  for (std::string rest = argv[3]; !rest.empty();) {
    const auto comma = rest.find(',');
    peers.push_back(rest.substr(0, comma));
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
  }
  const std::uint64_t run_id = std::strtoull(argv[4], nullptr, 16);
  const double seconds = std::atof(argv[5]);
  hostrun::set_environment(hostrun::write_unicast_dds_files(argv[6], {own, peers}));
  auto participant = transport::create_participant("cyclone", domain);
  auto requests = participant->create_agent_writer(transport::kAgentRequestTopic);
  auto replies = participant->create_agent_reader(transport::kAgentReplyTopic);
  int written = 0, answered = 0;
  std::vector<std::string> targets = peers;
  targets.push_back(hostrun::kAllAgents);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::uint64_t sequence = 0;
  while (std::chrono::steady_clock::now() < end) {
    for (const std::string& host : targets)
      for (const auto kind : {hostrun::AgentKind::start, hostrun::AgentKind::stop, hostrun::AgentKind::collect}) {
        transport::AgentMessage m;
        m.run_id = run_id;
        m.sequence = ++sequence;
        m.kind = static_cast<std::int32_t>(kind);
        m.host = host;
        m.node = "intruder";
        if (kind == hostrun::AgentKind::start)
          m.text = nlohmann::json{{"type", "follower"}, {"scene_yaml", ""}, {"run_folder", "outsider"}, {"domain", domain},
                                  {"address", host == hostrun::kAllAgents ? peers.front() : host}, {"peers", peers}}
                       .dump();
        requests->write(m);
        ++written;
      }
    participant->wait(std::chrono::milliseconds(200));
    while (replies->take()) ++answered;
  }
  std::printf("%s\n", nlohmann::json{{"requests", written}, {"replies", answered}, {"matched_readers", requests->matched_readers()}}
                          .dump()
                          .c_str());
  return 0;
}
