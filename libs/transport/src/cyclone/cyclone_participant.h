#pragma once

#include <map>
#include <string>

#include "dds/dds.h"
#include "mechsim/transport/participant.h"
#include "mechsim/transport/security.h"

namespace mechsim::transport::cyclone {

// One DDS domain participant with one waitset on which all its readers and a guard
// condition (for wake()) are attached. The domain's network configuration comes from
// CYCLONEDDS_URI, which the launcher sets (loopback only; config/dds/cyclonedds-loopback.xml).
class CycloneParticipant final : public Participant {
 public:
  CycloneParticipant(int domain_id, const std::optional<SecurityIdentity>& security);
  ~CycloneParticipant() override;
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
  std::string vendor() const override { return "cyclone"; }

 private:
  dds_entity_t topic(const std::string& name, const dds_topic_descriptor_t* desc);
  dds_entity_t attach_reader(dds_entity_t reader);
  std::unique_ptr<SampleWriter> data_writer(const std::string& topic, const TopicType& type, bool redundant);
  std::unique_ptr<SampleReader> data_reader(const std::string& topic, const TopicType& type, bool redundant);
  dds_entity_t participant_ = 0;
  dds_entity_t waitset_ = 0;
  dds_entity_t guard_ = 0;
  std::map<std::string, dds_entity_t> topics_;
};

}  // namespace mechsim::transport::cyclone
