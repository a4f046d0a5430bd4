#include "inproc_participant.h"

#include <algorithm>
#include <cstdint>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <stdexcept>

namespace mechsim::transport::inproc {

// Wakes a participant's wait(). Level-triggered like a DDS waitset: wait() returns at once
// while any reader of the participant holds an unread sample.
struct Notifier {
  std::mutex m;
  std::condition_variable cv;
  bool woken = false;
  std::atomic<long> unread{0};
  void signal() {
    { std::lock_guard<std::mutex> l(m); }  // orders the change before a waiter's predicate check
    cv.notify_all();
  }
};

struct DataQueue {
  std::string topic;
  const TopicType* type;
  std::shared_ptr<Notifier> notifier;
  std::deque<std::pair<SampleHeader, std::vector<double>>> samples;
};
struct ControlQueue {
  std::shared_ptr<Notifier> notifier;
  std::optional<ControlMessage> newest;  // KEEP_LAST 1
};
struct StatusQueue {
  std::shared_ptr<Notifier> notifier;
  std::deque<StatusMessage> samples;  // KEEP_LAST kStatusDepth
};
constexpr std::size_t kStatusDepth = 256;  // as Cyclone's status QoS (cyclone_qos.h)

struct Domain {
  std::mutex m;
  std::vector<DataQueue*> data_readers;
  std::map<std::pair<std::string, const TopicType*>, int> data_writers;
  std::vector<ControlQueue*> control_readers;
  int control_writers = 0;
  std::optional<ControlMessage> last_control;  // TRANSIENT_LOCAL
  std::vector<StatusQueue*> status_readers;
};

namespace {

std::shared_ptr<Domain> domain_for(int id) {
  static std::mutex registry_mutex;
  static std::map<int, std::weak_ptr<Domain>> registry;
  std::lock_guard<std::mutex> l(registry_mutex);
  auto& slot = registry[id];
  auto d = slot.lock();
  if (!d) slot = d = std::make_shared<Domain>();
  return d;
}

// The IDL bounds of the status strings (idl/control.idl: string<64> node, string<256> message).
std::string bounded(const std::string& s, std::size_t max) { return s.size() > max ? s.substr(0, max) : s; }

class Writer final : public SampleWriter {
 public:
  Writer(std::shared_ptr<Domain> d, std::string topic, const TopicType& type)
      : d_(std::move(d)), key_(std::move(topic), &type) {
    std::lock_guard<std::mutex> l(d_->m);
    ++d_->data_writers[key_];
  }
  ~Writer() override {
    std::lock_guard<std::mutex> l(d_->m);
    if (--d_->data_writers[key_] == 0) d_->data_writers.erase(key_);
  }
  void write(const SampleHeader& header, std::span<const double> values) override {
    const TopicType& type = *key_.second;
    if (values.size() != type.fields.size()) throw std::logic_error("write " + type.idl_name + ": wrong number of values");
    std::vector<double> v(values.begin(), values.end());
    as_on_the_wire(type, v);
    std::vector<Notifier*> to_wake;
    {
      std::lock_guard<std::mutex> l(d_->m);
      for (DataQueue* q : d_->data_readers)
        if (q->topic == key_.first && q->type->same_as(*key_.second)) {
          q->samples.emplace_back(header, v);
          ++q->notifier->unread;
          to_wake.push_back(q->notifier.get());
        }
    }
    for (Notifier* n : to_wake) n->signal();
  }
  int matched_readers() const override {
    std::lock_guard<std::mutex> l(d_->m);
    return static_cast<int>(std::count_if(d_->data_readers.begin(), d_->data_readers.end(), [&](const DataQueue* q) {
      return q->topic == key_.first && q->type->same_as(*key_.second);
    }));
  }
  // Delivery is complete when write() returns.
  void flush(std::chrono::nanoseconds) override {}

 private:
  std::shared_ptr<Domain> d_;
  std::pair<std::string, const TopicType*> key_;
};

class Reader final : public SampleReader {
 public:
  Reader(std::shared_ptr<Domain> d, std::shared_ptr<Notifier> n, std::string topic, const TopicType& type)
      : d_(std::move(d)) {
    q_.topic = std::move(topic);
    q_.type = &type;
    q_.notifier = std::move(n);
    std::lock_guard<std::mutex> l(d_->m);
    d_->data_readers.push_back(&q_);
  }
  ~Reader() override {
    std::lock_guard<std::mutex> l(d_->m);
    std::erase(d_->data_readers, &q_);
    q_.notifier->unread -= static_cast<long>(q_.samples.size());
  }
  bool take(SampleHeader& header, std::vector<double>& values) override {
    std::lock_guard<std::mutex> l(d_->m);
    if (q_.samples.empty()) return false;
    header = q_.samples.front().first;
    values.swap(q_.samples.front().second);
    q_.samples.pop_front();
    --q_.notifier->unread;
    return true;
  }
  int matched_writers() const override {
    std::lock_guard<std::mutex> l(d_->m);
    int n = 0;
    for (const auto& [key, count] : d_->data_writers)
      if (key.first == q_.topic && key.second->same_as(*q_.type)) n += count;
    return n;
  }

 private:
  std::shared_ptr<Domain> d_;
  DataQueue q_;
};

class CtlWriter final : public ControlWriter {
 public:
  explicit CtlWriter(std::shared_ptr<Domain> d) : d_(std::move(d)) {
    std::lock_guard<std::mutex> l(d_->m);
    ++d_->control_writers;
  }
  ~CtlWriter() override {
    std::lock_guard<std::mutex> l(d_->m);
    --d_->control_writers;
  }
  void write(const ControlMessage& message) override {
    std::vector<Notifier*> to_wake;
    {
      std::lock_guard<std::mutex> l(d_->m);
      d_->last_control = message;
      for (ControlQueue* q : d_->control_readers) {
        if (!q->newest) ++q->notifier->unread;
        q->newest = message;
        to_wake.push_back(q->notifier.get());
      }
    }
    for (Notifier* n : to_wake) n->signal();
  }
  int matched_readers() const override {
    std::lock_guard<std::mutex> l(d_->m);
    return static_cast<int>(d_->control_readers.size());
  }

 private:
  std::shared_ptr<Domain> d_;
};

class CtlReader final : public ControlReader {
 public:
  CtlReader(std::shared_ptr<Domain> d, std::shared_ptr<Notifier> n) : d_(std::move(d)) {
    q_.notifier = std::move(n);
    std::lock_guard<std::mutex> l(d_->m);
    d_->control_readers.push_back(&q_);
    // A late joiner gets the last command (TRANSIENT_LOCAL, KEEP_LAST 1), while a writer
    // of it is alive (as with DDS, where the writer keeps the durable sample).
    if (d_->last_control && d_->control_writers > 0) {
      q_.newest = d_->last_control;
      ++q_.notifier->unread;
    }
  }
  ~CtlReader() override {
    std::lock_guard<std::mutex> l(d_->m);
    std::erase(d_->control_readers, &q_);
    if (q_.newest) --q_.notifier->unread;
  }
  std::optional<ControlMessage> take() override {
    std::lock_guard<std::mutex> l(d_->m);
    std::optional<ControlMessage> m;
    m.swap(q_.newest);
    if (m) --q_.notifier->unread;
    return m;
  }

 private:
  std::shared_ptr<Domain> d_;
  ControlQueue q_;
};

class StWriter final : public StatusWriter {
 public:
  explicit StWriter(std::shared_ptr<Domain> d) : d_(std::move(d)) {}
  void write(const StatusMessage& message) override {
    StatusMessage m = message;
    m.node = bounded(m.node, 64);
    m.message = bounded(m.message, 256);
    std::vector<Notifier*> to_wake;
    {
      std::lock_guard<std::mutex> l(d_->m);
      for (StatusQueue* q : d_->status_readers) {
        if (q->samples.size() == kStatusDepth) {
          q->samples.pop_front();  // best effort, KEEP_LAST: the oldest goes
        } else {
          ++q->notifier->unread;
        }
        q->samples.push_back(m);
        to_wake.push_back(q->notifier.get());
      }
    }
    for (Notifier* n : to_wake) n->signal();
  }

 private:
  std::shared_ptr<Domain> d_;
};

class StReader final : public StatusReader {
 public:
  StReader(std::shared_ptr<Domain> d, std::shared_ptr<Notifier> n) : d_(std::move(d)) {
    q_.notifier = std::move(n);
    std::lock_guard<std::mutex> l(d_->m);
    d_->status_readers.push_back(&q_);
  }
  ~StReader() override {
    std::lock_guard<std::mutex> l(d_->m);
    std::erase(d_->status_readers, &q_);
    q_.notifier->unread -= static_cast<long>(q_.samples.size());
  }
  std::optional<StatusMessage> take() override {
    std::lock_guard<std::mutex> l(d_->m);
    if (q_.samples.empty()) return std::nullopt;
    StatusMessage m = std::move(q_.samples.front());
    q_.samples.pop_front();
    --q_.notifier->unread;
    return m;
  }

 private:
  std::shared_ptr<Domain> d_;
  StatusQueue q_;
};

}  // namespace

InprocParticipant::InprocParticipant(int domain_id)
    : domain_(domain_for(domain_id)), notifier_(std::make_shared<Notifier>()) {}

InprocParticipant::~InprocParticipant() = default;

std::unique_ptr<SampleWriter> InprocParticipant::create_writer(const std::string& topic, const TopicType& type) {
  return std::make_unique<Writer>(domain_, topic, type);
}
std::unique_ptr<SampleReader> InprocParticipant::create_reader(const std::string& topic, const TopicType& type) {
  return std::make_unique<Reader>(domain_, notifier_, topic, type);
}
std::unique_ptr<ControlWriter> InprocParticipant::create_control_writer() { return std::make_unique<CtlWriter>(domain_); }
std::unique_ptr<ControlReader> InprocParticipant::create_control_reader() {
  return std::make_unique<CtlReader>(domain_, notifier_);
}
std::unique_ptr<StatusWriter> InprocParticipant::create_status_writer() { return std::make_unique<StWriter>(domain_); }
std::unique_ptr<StatusReader> InprocParticipant::create_status_reader() {
  return std::make_unique<StReader>(domain_, notifier_);
}

bool InprocParticipant::wait(std::chrono::nanoseconds timeout) {
  Notifier& n = *notifier_;
  std::unique_lock<std::mutex> l(n.m);
  const bool got = n.cv.wait_for(l, timeout, [&] { return n.woken || n.unread.load() > 0; });
  n.woken = false;
  return got;
}

void InprocParticipant::wake() {
  {
    std::lock_guard<std::mutex> l(notifier_->m);
    notifier_->woken = true;
  }
  notifier_->cv.notify_all();
}

}  // namespace mechsim::transport::inproc
