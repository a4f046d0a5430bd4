// The transport seam. One Participant per process; node logic and the launcher use only
// these interfaces, never DDS types. Backends: cyclone (DDS, default) — see backends.h.
//
// QoS contract every backend honours (docs/dds.md):
//  - data topics: RELIABLE, KEEP_ALL on writer and reader (no step is ever overwritten
//    unread; a writer blocks when its history is full), VOLATILE;
//  - mechsim/control: RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1 (a late joiner sees the last
//    command);
//  - mechsim/status: BEST_EFFORT, KEEP_LAST (a heartbeat: losing one is harmless);
//  - mechsim/agent/request and /reply: RELIABLE, KEEP_ALL, VOLATILE (docs/hosts.md).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mechsim/transport/messages.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::transport {

class SampleWriter {
 public:
  virtual ~SampleWriter() = default;
  // values: one per field of the topic type, in field order.
  virtual void write(const SampleHeader& header, std::span<const double> values) = 0;
  // Readers matched with this writer, not counting mechsim tools' readers (recorder,
  // `topic echo`; they carry USER_DATA "mechsim:tool", raw.h): what readiness waits for.
  virtual int matched_readers() const = 0;
  // Every matched reader, tools' readers included (the launcher's recorder must have
  // matched before a recorded run starts).
  virtual int matched_readers_including_tools() const { return matched_readers(); }
  // The readers matched over the transport itself, tools' included: what a discovery of the
  // domain counts (the launcher's readers barrier). Not a reader of the same process that
  // takes the samples from memory (local_handoff.h), which the two counts above include.
  virtual int matched_readers_on_the_wire() const { return matched_readers_including_tools(); }
  // Waits until every matched reader acknowledged what was written (before a node exits).
  virtual void flush(std::chrono::nanoseconds timeout) = 0;
};

class SampleReader {
 public:
  virtual ~SampleReader() = default;
  // Takes the next sample if there is one (values resized to the field count).
  virtual bool take(SampleHeader& header, std::vector<double>& values) = 0;
  virtual int matched_writers() const = 0;
  // The writers matched with this reader as far as the vendor tells: "GUID <hex>" and, for
  // a Cyclone DDS writer, "process <name> (pid <n>) on <host>". For failure messages.
  virtual std::vector<std::string> matched_writer_ids() const { return {}; }
};

class ControlWriter {
 public:
  virtual ~ControlWriter() = default;
  virtual void write(const ControlMessage& message) = 0;
  virtual int matched_readers() const = 0;
  // This writer's GUID (guid_text): the launcher hands it to its nodes, which then take
  // commands from nobody else; "" where the transport has none (in process).
  virtual std::string guid() const { return {}; }
};

class ControlReader {
 public:
  virtual ~ControlReader() = default;
  // The next command, with ControlMessage::writer set to the sender's GUID where known.
  virtual std::optional<ControlMessage> take() = 0;
  // Writers of mechsim/control matched with this reader (the launcher: one); -1 = unknown.
  virtual int matched_writers() const { return -1; }
  virtual std::vector<std::string> matched_writer_ids() const { return {}; }
};

class StatusWriter {
 public:
  virtual ~StatusWriter() = default;
  virtual void write(const StatusMessage& message) = 0;
};

class StatusReader {
 public:
  virtual ~StatusReader() = default;
  virtual std::optional<StatusMessage> take() = 0;
};

class AgentWriter {
 public:
  virtual ~AgentWriter() = default;
  virtual void write(const AgentMessage& message) = 0;
  virtual int matched_readers() const = 0;
};

class AgentReader {
 public:
  virtual ~AgentReader() = default;
  virtual std::optional<AgentMessage> take() = 0;
};

class Participant {
 public:
  virtual ~Participant() = default;
  virtual std::unique_ptr<SampleWriter> create_writer(const std::string& topic, const TopicType& type) = 0;
  virtual std::unique_ptr<SampleReader> create_reader(const std::string& topic, const TopicType& type) = 0;
  // The best-effort twin of a data topic (redundant_topic(topic); BEST_EFFORT, KEEP_LAST
  // 64): a node that publishes every sample on both lets its partners take whichever copy
  // arrives first, so a lost packet costs nothing unless both copies are lost
  // (docs/faults.md). nullptr where the backend has no network to lose packets on
  // (in-process).
  virtual std::unique_ptr<SampleWriter> create_redundant_writer(const std::string& topic, const TopicType& type);
  virtual std::unique_ptr<SampleReader> create_redundant_reader(const std::string& topic, const TopicType& type);
  virtual std::unique_ptr<ControlWriter> create_control_writer() = 0;
  virtual std::unique_ptr<ControlReader> create_control_reader() = 0;
  virtual std::unique_ptr<StatusWriter> create_status_writer() = 0;
  virtual std::unique_ptr<StatusReader> create_status_reader() = 0;
  // The agent conversation (kAgentRequestTopic or kAgentReplyTopic). The DDS backends have
  // it; the in-process one, which never leaves the process, throws std::logic_error.
  virtual std::unique_ptr<AgentWriter> create_agent_writer(const std::string& topic);
  virtual std::unique_ptr<AgentReader> create_agent_reader(const std::string& topic);
  // Blocks until any reader created by this participant may have data, wake() is called,
  // or the timeout passes. Returns false on timeout. Spurious wake-ups are allowed.
  virtual bool wait(std::chrono::nanoseconds timeout) = 0;
  // Interrupts wait() (safe to call from another thread).
  virtual void wake() = 0;
  virtual std::string vendor() const = 0;
};

}  // namespace mechsim::transport
