// The in-process backend: every participant of a "domain" lives in this process (the
// design's inproc transport: all nodes of a scene as threads of one process, for fast
// sweeps and composition). Samples travel through in-memory queues with the QoS contract
// of participant.h:
//  - data topics: RELIABLE, KEEP_ALL, VOLATILE: a write is queued for every reader of the
//    topic (same topic name and type) that exists at that moment, none is ever dropped;
//    a reader created later sees only later samples;
//  - mechsim/control: RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1: the domain keeps the last
//    command and hands it to a control reader created later; a reader keeps only the
//    newest command not yet taken;
//  - mechsim/status: BEST_EFFORT, KEEP_LAST 256 per reader (the oldest is dropped when a
//    reader falls that far behind, as Cyclone would).
// Values go through the same conversions as on the wire (booleans become 0/1, strings
// are cut to the IDL bounds), so a node sees exactly what DDS would have given it.
// Domains are separate per domain id and exist while a participant of them does.
#pragma once

#include <memory>

#include "mechsim/transport/participant.h"

namespace mechsim::transport::inproc {

struct Domain;
struct Notifier;

class InprocParticipant final : public Participant {
 public:
  explicit InprocParticipant(int domain_id);
  ~InprocParticipant() override;
  std::unique_ptr<SampleWriter> create_writer(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<SampleReader> create_reader(const std::string& topic, const TopicType& type) override;
  std::unique_ptr<ControlWriter> create_control_writer() override;
  std::unique_ptr<ControlReader> create_control_reader() override;
  std::unique_ptr<StatusWriter> create_status_writer() override;
  std::unique_ptr<StatusReader> create_status_reader() override;
  bool wait(std::chrono::nanoseconds timeout) override;
  void wake() override;
  std::string vendor() const override { return "inproc"; }

 private:
  std::shared_ptr<Domain> domain_;
  std::shared_ptr<Notifier> notifier_;
};

}  // namespace mechsim::transport::inproc
