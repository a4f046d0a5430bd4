#pragma once

#include <memory>
#include <string>

#include "mechsim/transport/participant.h"

namespace mechsim::transport::fastdds {

struct FastCore;

// Where the participants of a domain keep their data-sharing segments (a folder in /dev/shm
// per user and domain).
std::string data_sharing_dir(int domain_id);
// After a run of `domain_id` whose processes have all exited: removes the domain's
// data-sharing folder and runs `fastdds shm clean` (if installed) for the transport's
// segments of processes that are gone.
void clean_shared_memory(int domain_id);

// One Fast DDS DomainParticipant (C++ DDS API of Fast DDS 2.9) with one publisher and one
// subscriber. Transports come from the XML profile in FASTRTPS_DEFAULT_PROFILES_FILE, which
// the launcher sets (config/dds/fastdds-shm.xml or fastdds-udp.xml: loopback only).
// wait()/wake(): every reader carries a listener that raises a flag under a mutex and
// notifies a condition variable; wait() sleeps on it (the Fast DDS 2.9 WaitSet has no
// working ReadCondition, and a listener sees every sample, whichever thread delivers it:
// a transport's receive thread or the data-sharing listener).
class FastParticipant final : public Participant {
 public:
  explicit FastParticipant(int domain_id);
  ~FastParticipant() override;
  std::unique_ptr<SampleWriter> create_writer(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<SampleReader> create_reader(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<ControlWriter> create_control_writer() override;
  std::unique_ptr<ControlReader> create_control_reader() override;
  std::unique_ptr<StatusWriter> create_status_writer() override;
  std::unique_ptr<StatusReader> create_status_reader() override;
  bool wait(std::chrono::nanoseconds timeout) override;
  void wake() override;
  std::string vendor() const override { return "fastdds"; }

 private:
  // Shared with every writer and reader, so they may outlive this object safely.
  std::shared_ptr<FastCore> core_;
};

}  // namespace mechsim::transport::fastdds
