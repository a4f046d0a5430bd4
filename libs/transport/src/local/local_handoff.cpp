#include "mechsim/transport/local_handoff.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <map>
#include <utility>
#include <vector>

namespace mechsim::transport {

namespace {

struct Queue {
  const TopicType* type;
  std::deque<std::pair<SampleHeader, std::vector<double>>> samples;
  // Value buffers of taken samples, reused by the next writes: a step hands a sample over
  // without allocating (the queue holds a step or two).
  std::vector<std::vector<double>> spare;
};

}  // namespace

// Per local topic: its readers' queues and how many writers of it exist.
struct LocalHandoff::Bus {
  struct Topic {
    std::vector<Queue*> readers;
    std::vector<std::pair<const void*, const TopicType*>> writers;  // (writer, its type)
  };
  std::map<std::string, Topic> topics;
};

namespace {

using Bus = LocalHandoff::Bus;

int count_same(const std::vector<std::pair<const void*, const TopicType*>>& writers, const TopicType& type) {
  return static_cast<int>(std::count_if(writers.begin(), writers.end(), [&](const auto& w) { return w.second->same_as(type); }));
}

// Hands each sample to the local readers of its topic and publishes it on DDS while anyone
// outside reads it (a tool, a recorder, a member of another process or host). Every reader
// of a run matched before its start (the launcher's barriers), so nobody who counts misses a
// sample; a reader that matches later (`topic echo`, a restarted partner) is seen within
// kRecheckWrites writes or kRecheckPeriod, as a late joiner of a VOLATILE topic expects.
class HandoffWriter final : public SampleWriter {
 public:
  HandoffWriter(Bus::Topic& topic, const TopicType& type, std::unique_ptr<SampleWriter> dds)
      : topic_(topic), type_(type), dds_(std::move(dds)) {
    topic_.writers.emplace_back(this, &type_);
  }
  ~HandoffWriter() override {
    std::erase_if(topic_.writers, [this](const auto& w) { return w.first == this; });
  }
  void write(const SampleHeader& header, std::span<const double> values) override {
    if (read_outside()) dds_->write(header, values);
    for (Queue* q : topic_.readers)
      if (q->type->same_as(type_)) {
        std::vector<double> buffer;
        if (!q->spare.empty()) {
          buffer = std::move(q->spare.back());
          q->spare.pop_back();
        }
        buffer.assign(values.begin(), values.end());
        as_on_the_wire(type_, buffer);
        q->samples.emplace_back(header, std::move(buffer));
      }
  }
  int matched_readers() const override { return dds_->matched_readers() + local_readers(); }
  int matched_readers_including_tools() const override { return dds_->matched_readers_including_tools() + local_readers(); }
  int matched_readers_on_the_wire() const override { return dds_->matched_readers_on_the_wire(); }
  void flush(std::chrono::nanoseconds timeout) override { dds_->flush(timeout); }

 private:
  static constexpr int kRecheckWrites = 16;
  static constexpr std::chrono::milliseconds kRecheckPeriod{5};
  bool read_outside() {
    const auto now = std::chrono::steady_clock::now();
    if (--writes_to_recheck_ <= 0 || now - checked_at_ > kRecheckPeriod) {
      read_outside_ = dds_->matched_readers_including_tools() > 0;
      writes_to_recheck_ = kRecheckWrites;
      checked_at_ = now;
    }
    return read_outside_;
  }
  int local_readers() const {
    return static_cast<int>(std::count_if(topic_.readers.begin(), topic_.readers.end(),
                                          [&](const Queue* q) { return q->type->same_as(type_); }));
  }
  Bus::Topic& topic_;
  const TopicType& type_;
  std::unique_ptr<SampleWriter> dds_;
  bool read_outside_ = true;
  int writes_to_recheck_ = 0;
  std::chrono::steady_clock::time_point checked_at_{};
};

class HandoffReader final : public SampleReader {
 public:
  HandoffReader(Bus::Topic& topic, const TopicType& type) : topic_(topic) {
    queue_.type = &type;
    topic_.readers.push_back(&queue_);
  }
  ~HandoffReader() override { std::erase(topic_.readers, &queue_); }
  bool take(SampleHeader& header, std::vector<double>& values) override {
    if (queue_.samples.empty()) return false;
    header = queue_.samples.front().first;
    values.swap(queue_.samples.front().second);
    queue_.spare.push_back(std::move(queue_.samples.front().second));  // the caller's old buffer
    queue_.samples.pop_front();
    return true;
  }
  int matched_writers() const override { return count_same(topic_.writers, *queue_.type); }
  std::vector<std::string> matched_writer_ids() const override {
    return std::vector<std::string>(matched_writers(), "a participant of this process (in-memory hand-off)");
  }

 private:
  Bus::Topic& topic_;
  Queue queue_;
};

// The best-effort twin of a local topic: a copy for other hosts only; nothing arrives here.
class SilentReader final : public SampleReader {
 public:
  bool take(SampleHeader&, std::vector<double>&) override { return false; }
  int matched_writers() const override { return 1; }
};

class MemberParticipant final : public Participant {
 public:
  MemberParticipant(LocalHandoff& handoff, Bus& bus, std::unique_ptr<Participant> own)
      : handoff_(handoff), bus_(bus), own_(std::move(own)) {}
  std::unique_ptr<SampleWriter> create_writer(const std::string& topic, const TopicType& type) override {
    if (!handoff_.is_local(topic)) return own_->create_writer(topic, type);
    return std::make_unique<HandoffWriter>(bus_.topics[topic], type, own_->create_writer(topic, type));
  }
  std::unique_ptr<SampleReader> create_reader(const std::string& topic, const TopicType& type) override {
    if (!handoff_.is_local(topic)) return own_->create_reader(topic, type);
    return std::make_unique<HandoffReader>(bus_.topics[topic], type);
  }
  std::unique_ptr<SampleWriter> create_redundant_writer(const std::string& topic, const TopicType& type) override {
    return own_->create_redundant_writer(topic, type);
  }
  std::unique_ptr<SampleReader> create_redundant_reader(const std::string& topic, const TopicType& type) override {
    if (!handoff_.is_local(topic)) return own_->create_redundant_reader(topic, type);
    return std::make_unique<SilentReader>();
  }
  std::unique_ptr<ControlWriter> create_control_writer() override { return own_->create_control_writer(); }
  std::unique_ptr<ControlReader> create_control_reader() override { return own_->create_control_reader(); }
  std::unique_ptr<StatusWriter> create_status_writer() override { return own_->create_status_writer(); }
  std::unique_ptr<StatusReader> create_status_reader() override { return own_->create_status_reader(); }
  std::unique_ptr<AgentWriter> create_agent_writer(const std::string& topic) override { return own_->create_agent_writer(topic); }
  std::unique_ptr<AgentReader> create_agent_reader(const std::string& topic) override { return own_->create_agent_reader(topic); }
  bool wait(std::chrono::nanoseconds timeout) override { return own_->wait(timeout); }
  void wake() override { own_->wake(); }
  std::string vendor() const override { return own_->vendor(); }

 private:
  LocalHandoff& handoff_;
  Bus& bus_;
  std::unique_ptr<Participant> own_;
};

}  // namespace

LocalHandoff::LocalHandoff(std::set<std::string> local_topics) : topics_(std::move(local_topics)), bus_(std::make_unique<Bus>()) {}

LocalHandoff::~LocalHandoff() = default;

std::unique_ptr<Participant> LocalHandoff::member(std::unique_ptr<Participant> own) {
  return std::make_unique<MemberParticipant>(*this, *bus_, std::move(own));
}

}  // namespace mechsim::transport
