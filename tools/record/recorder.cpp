#include "recorder.h"

#include <atomic>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "cdr_decoder.h"
#include "mechsim/config/scene.h"
#include "idl_schema.h"
#include "mechsim/transport/raw.h"

namespace mechsim::recorder {

void TopicSelection::validate() const {
  if (!names.empty() && !regex.empty()) throw std::invalid_argument("give either topic names or a regex, not both");
  if (!regex.empty()) {
    try {
      std::regex check(regex, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      throw std::invalid_argument("bad topic regex '" + regex + "': " + e.what());
    }
  }
}

bool TopicSelection::selects(const std::string& topic) const { return config::topic_selected(names, regex, topic); }

record::Compression parse_compression(const std::string& name) {
  if (name == "zstd") return record::Compression::zstd;
  if (name == "lz4") return record::Compression::lz4;
  if (name == "none" || name.empty()) return record::Compression::none;
  throw std::invalid_argument("unknown compression '" + name + "' (expected zstd, lz4 or none)");
}

namespace {

using SystemClock = std::chrono::system_clock;
using SteadyClock = std::chrono::steady_clock;

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(SystemClock::now().time_since_epoch()).count());
}

// MCAP publish time: the sample's simulated time in ns (negative or non-finite times,
// which mechsim never publishes, map to 0).
std::uint64_t simulated_ns(double t) {
  if (!(t > 0.0)) return 0;
  const double ns = std::round(t * 1e9);
  return ns >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(ns);
}

std::string qos_text(transport::TopicKind kind) {
  switch (kind) {
    case transport::TopicKind::data: return "reliable, keep all, volatile";
    case transport::TopicKind::control: return "reliable, keep last 1, transient local";
    case transport::TopicKind::status: return "best effort, keep last 256, volatile";
  }
  return "";
}

class RecorderImpl final : public Recorder {
 public:
  RecorderImpl(int domain_id, const RecordOptions& options) : options_(options), started_(SteadyClock::now()) {
    options_.topics.validate();
    participant_ = transport::create_raw_participant(options_.vendor, domain_id);
    for (const auto& [topic, type] : options_.topic_types) {
      if (!options_.topics.selects(topic))
        throw std::invalid_argument("topic " + topic + " has a type given but is not selected for recording");
      if (!find_layout(type)) throw std::invalid_argument("topic " + topic + ": unknown type '" + type + "'");
    }
    record::WriterOptions w;
    w.compression = options_.compression;
    w.max_chunk_interval = options_.max_chunk_interval;
    w.sync = options_.sync;
    writer_ = std::make_unique<record::McapWriter>(options_.file, w);
    for (const auto& [topic, type] : options_.topic_types) subscribe(topic, *find_layout(type));
    thread_ = std::thread([this] { run(); });
  }

  ~RecorderImpl() override { stop(); }

  bool wait_matched(const std::vector<std::string>& topics, std::chrono::milliseconds timeout) override {
    const auto deadline = SteadyClock::now() + timeout;
    for (;;) {
      if (all_matched(topics)) return true;
      if (SteadyClock::now() > deadline || finished_) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }

  std::vector<TopicCount> counts() const override {
    std::lock_guard lock(mutex_);
    std::vector<TopicCount> out;
    for (const auto& [name, s] : subscriptions_) {
      TopicCount c;
      c.topic = name;
      c.type = s->layout->type_name;
      c.reliable = transport::topic_kind(name) != transport::TopicKind::status;
      c.samples = s->samples.load();
      c.lost = s->lost.load();
      c.repeated = s->repeated.load();
      c.matched_writers = s->reader->matched_writers();
      out.push_back(c);
    }
    return out;
  }

  RecordingReport stop() override {
    std::lock_guard lock(stop_mutex_);
    if (!thread_.joinable()) return report_;
    stop_requested_ = true;
    participant_->wake();
    thread_.join();
    report_.file = options_.file;
    report_.topics = counts();
    for (const auto& t : report_.topics) report_.messages += t.samples;
    std::error_code ec;
    report_.bytes = std::filesystem::file_size(options_.file, ec);
    report_.wall_time_s = std::chrono::duration<double>(SteadyClock::now() - started_).count();
    return report_;
  }

  const std::string& file() const override { return options_.file; }

 private:
  struct Subscription {
    std::unique_ptr<transport::RawReader> reader;
    const MessageLayout* layout = nullptr;
    std::uint16_t channel = 0;
    std::uint32_t sequence = 0;
    std::atomic<std::uint64_t> samples{0};
    std::atomic<std::uint64_t> lost{0};
    std::atomic<std::uint64_t> repeated{0};
    bool data = false;
    std::map<std::uint64_t, std::uint64_t> next_step;  // data topics: run id -> the step after the newest recorded
  };

  bool all_matched(const std::vector<std::string>& topics) const {
    std::lock_guard lock(mutex_);
    for (const auto& t : topics) {
      auto it = subscriptions_.find(t);
      if (it == subscriptions_.end() || it->second->reader->matched_writers() < 1) return false;
    }
    return true;
  }

  // Reader, schema (once per type) and channel of one topic. Recording thread (or the
  // constructor, before it starts).
  void subscribe(const std::string& topic, const MessageLayout& layout) {
    auto s = std::make_unique<Subscription>();
    s->layout = &layout;
    s->reader = participant_->create_reader(topic, layout.type_name);
    s->data = transport::topic_kind(topic) == transport::TopicKind::data;
    auto schema = schemas_.find(layout.type_name);
    if (schema == schemas_.end())
      schema = schemas_.emplace(layout.type_name, writer_->add_schema(layout.type_name, "omgidl", schema_text(layout))).first;
    std::map<std::string, std::string> metadata{{"qos", qos_text(transport::topic_kind(topic))}};
    if (auto it = options_.topic_fields.find(topic); it != options_.topic_fields.end()) metadata[kFieldsMetadataKey] = it->second;
    s->channel = writer_->add_channel(schema->second, topic, "cdr", metadata);
    std::lock_guard lock(mutex_);
    subscriptions_.emplace(topic, std::move(s));
  }

  // Subscribes to selected topics of known types that a writer announced since last time.
  void follow_discovery() {
    for (const auto& t : participant_->discovered_topics()) {
      if (t.publishers == 0 || subscriptions_.count(t.name) || !options_.topics.selects(t.name)) continue;
      if (const MessageLayout* layout = find_layout(t.type_name); layout && layout->type_name == t.type_name)
        subscribe(t.name, *layout);
    }
  }

  // Returns how many samples it wrote.
  std::uint64_t drain() {
    std::uint64_t n = 0;
    for (auto& [name, s] : subscriptions_) {
      while (s->reader->take(sample_)) {
        // A step's first copy only: after a rollback the nodes send the steps since the
        // checkpoint again (with the same values), and the file stays that of one run.
        if (s->data) {
          std::uint64_t& next = s->next_step[sample_.header.run_id];
          if (sample_.header.step < next) {
            s->repeated.fetch_add(1, std::memory_order_relaxed);
            continue;
          }
          next = sample_.header.step + 1;
        }
        writer_->write(s->channel, s->sequence++, now_ns(), simulated_ns(sample_.header.t), sample_.cdr);
        s->samples.fetch_add(1, std::memory_order_relaxed);
        ++n;
      }
    }
    return n;
  }

  void update_lost() {
    for (auto& [name, s] : subscriptions_) s->lost.store(s->reader->lost_samples());
  }

  void run() {
    try {
      std::uint64_t seen_discovery = ~std::uint64_t{0};
      auto last_housekeeping = SteadyClock::now(), last_rescan = SteadyClock::now();
      while (!stop_requested_) {
        participant_->wait(options_.flush_period);
        // On every discovery event, and once a second in case one was missed.
        if (participant_->discovery_events() != seen_discovery || SteadyClock::now() - last_rescan > std::chrono::seconds(1)) {
          seen_discovery = participant_->discovery_events();
          last_rescan = SteadyClock::now();
          follow_discovery();
        }
        const bool busy = drain() > 0;
        if (SteadyClock::now() - last_housekeeping >= options_.flush_period) {
          writer_->flush_if_due();
          update_lost();
          last_housekeeping = SteadyClock::now();
        }
        if (busy && options_.batch_period.count() > 0) std::this_thread::sleep_for(options_.batch_period);
      }
      // What the readers still hold: writers that finished waited for our acknowledgement,
      // so everything they wrote is here.
      drain();
      update_lost();
      writer_->close();
    } catch (const std::exception& e) {
      report_.error = e.what();
      try {
        writer_->close();
      } catch (const std::exception& e2) {
        report_.error += std::string("; closing the file: ") + e2.what();
      }
    }
    finished_ = true;
  }

  RecordOptions options_;
  SteadyClock::time_point started_;
  std::unique_ptr<transport::RawParticipant> participant_;
  std::unique_ptr<record::McapWriter> writer_;
  std::map<std::string, std::uint16_t> schemas_;  // type -> schema id
  // Changed only by the recording thread (under the mutex); read by others under it.
  std::map<std::string, std::unique_ptr<Subscription>> subscriptions_;
  mutable std::mutex mutex_;
  transport::RawSample sample_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> finished_{false};
  std::mutex stop_mutex_;
  RecordingReport report_;
  std::thread thread_;
};

}  // namespace

std::unique_ptr<Recorder> start_recording(int domain_id, const RecordOptions& options) {
  return std::make_unique<RecorderImpl>(domain_id, options);
}

}  // namespace mechsim::recorder
