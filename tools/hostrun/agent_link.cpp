#include "agent_link.h"

#include <cstdlib>

#include "hosts.h"
#include "install_paths.h"
#include "ssh_agent_link.h"

namespace mechsim::hostrun {

namespace {

class DdsAgentLink : public AgentLink {
 public:
  explicit DdsAgentLink(transport::Participant& p)
      : participant_(p),
        requests_(p.create_agent_writer(transport::kAgentRequestTopic)),
        replies_(p.create_agent_reader(transport::kAgentReplyTopic)) {}
  void send(const transport::AgentMessage& m) override { requests_->write(m); }
  std::optional<transport::AgentMessage> take() override { return replies_->take(); }
  bool reaches(std::size_t agents) const override { return requests_->matched_readers() >= static_cast<int>(agents); }
  void wait(std::chrono::milliseconds timeout) override { participant_.wait(timeout); }
  bool gone(const std::string&) const override { return false; }  // a daemon may start late
  std::string problem(const std::string&) const override { return ""; }

 private:
  transport::Participant& participant_;
  std::unique_ptr<transport::AgentWriter> requests_;
  std::unique_ptr<transport::AgentReader> replies_;
};

}  // namespace

std::unique_ptr<AgentLink> dds_agent_link(transport::Participant& participant) { return std::make_unique<DdsAgentLink>(participant); }

std::unique_ptr<AgentLink> open_agent_link(const HostLayout& hosts, transport::Participant& participant, int domain,
                                           const std::string& run_dir) {
  if (!hosts.over_ssh) return dds_agent_link(participant);
  const char* ssh = std::getenv("MECHSIM_SSH");
  std::vector<SshSession> sessions;
  for (const auto& [address, h] : hosts.remote_hosts)
    sessions.push_back({address,
                        ssh_agent_command(ssh ? ssh : "ssh", h.ssh_config, h.ssh.empty() ? address : h.ssh,
                                          h.mechsim.empty() ? executable_dir() + "/mechsim" : h.mechsim, domain),
                        run_dir + "/ssh-" + h.name + ".log"});
  return ssh_agent_link(sessions);
}

}  // namespace mechsim::hostrun
