#pragma once

#include <memory>
#include <string>

#include "mechsim/transport/participant.h"
#include "mechsim/transport/security.h"

namespace mechsim::transport::fastdds {

struct FastCore;

// After a run whose processes have all exited, some perhaps killed: runs `fastdds shm
// clean` (fastdds-tools, if installed), which removes the shared-memory transport's
// segments of processes that are gone.
void clean_shared_memory();

// One Fast DDS DomainParticipant (C++ DDS API of Fast DDS 2.9) with one publisher and one
// subscriber. Transports come from the XML profile in FASTRTPS_DEFAULT_PROFILES_FILE, which
// the launcher sets (config/dds/fastdds-shm.xml or fastdds-udp.xml: loopback only).
// wait()/wake(): one WaitSet with a ReadCondition per reader (any sample state, so it
// triggers while a reader holds a sample, like Cyclone's) and a GuardCondition for wake().
// share_in_process: the DomainParticipant is the one every other sharing FastParticipant of
// this process on the same domain and identity uses (a process group's members).
class FastParticipant final : public Participant {
 public:
  FastParticipant(int domain_id, const std::optional<SecurityIdentity>& security, bool share_in_process = false);
  ~FastParticipant() override;
  std::unique_ptr<SampleWriter> create_writer(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<SampleReader> create_reader(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<SampleWriter> create_redundant_writer(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<SampleReader> create_redundant_reader(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<ControlWriter> create_control_writer() override;
  std::unique_ptr<ControlReader> create_control_reader() override;
  std::unique_ptr<StatusWriter> create_status_writer() override;
  std::unique_ptr<StatusReader> create_status_reader() override;
  std::unique_ptr<AgentWriter> create_agent_writer(const std::string& topic) override;
  std::unique_ptr<AgentReader> create_agent_reader(const std::string& topic) override;
  bool wait(std::chrono::nanoseconds timeout) override;
  void wake() override;
  std::string vendor() const override { return "fastdds"; }

 private:
  // Shared with every writer and reader, so they may outlive this object safely.
  std::shared_ptr<FastCore> core_;
};

}  // namespace mechsim::transport::fastdds
