#include "domain_source.h"

#include <cmath>
#include <stdexcept>

#include "cdr_decoder.h"
#include "idl_schema.h"
#include "mechsim/transport/raw.h"

namespace mechsim::live {

struct DomainSource::Subscription {
  std::unique_ptr<transport::RawReader> reader;
  std::string type;
  std::uint32_t channel = 0;
};

namespace {
// Simulation time in ns, as the recorder stamps a message (negative or non-finite: 0).
std::uint64_t simulated_ns(double t) {
  if (!(t > 0.0)) return 0;
  const double ns = std::round(t * 1e9);
  return ns >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(ns);
}
}  // namespace

DomainSource::DomainSource(LiveServer& server, const DomainSourceOptions& options) : server_(server), options_(options) {
  options_.topics.validate();
  for (const auto& [topic, type] : options_.topic_types)
    if (!recorder::find_layout(type)) throw std::invalid_argument("topic " + topic + ": unknown type '" + type + "'");
  participant_ = transport::create_raw_participant("cyclone", options_.domain);
  for (const auto& [topic, type] : options_.topic_types)
    if (options_.topics.selects(topic)) subscribe(topic, *recorder::find_layout(type));
  thread_ = std::thread([this] { run(); });
}

DomainSource::~DomainSource() {
  stop_ = true;
  participant_->wake();
  if (thread_.joinable()) thread_.join();
}

std::map<std::pair<std::string, std::string>, int> DomainSource::readers() const {
  std::lock_guard lock(mutex_);
  std::map<std::pair<std::string, std::string>, int> out;
  for (const auto& [topic, s] : subscriptions_) ++out[{topic, s->type}];
  return out;
}

void DomainSource::subscribe(const std::string& topic, const recorder::MessageLayout& layout) {
  auto s = std::make_unique<Subscription>();
  s->reader = participant_->create_reader(topic, layout.type_name);
  s->type = layout.type_name;
  ChannelInfo info;
  info.topic = topic;
  info.schema_name = layout.type_name;
  info.schema = recorder::schema_text(layout);
  // An FMU participant's variable names, which its sequences do not carry (docs/live.md).
  if (auto it = options_.topic_fields.find(topic); it != options_.topic_fields.end())
    info.metadata[recorder::kFieldsMetadataKey] = it->second;
  s->channel = server_.add_channel(std::move(info));
  std::lock_guard lock(mutex_);
  subscriptions_.emplace(topic, std::move(s));
}

void DomainSource::run() {
  transport::RawSample sample;
  std::uint64_t seen_discovery = ~std::uint64_t{0};
  while (!stop_) {
    participant_->wait(std::chrono::milliseconds(100));
    if (participant_->discovery_events() != seen_discovery) {
      seen_discovery = participant_->discovery_events();
      for (const auto& t : participant_->discovered_topics()) {
        if (t.publishers == 0 || subscriptions_.count(t.name) || !options_.topics.selects(t.name)) continue;
        if (const auto* layout = recorder::find_layout(t.type_name); layout && layout->type_name == t.type_name)
          subscribe(t.name, *layout);
      }
    }
    bool took = false;
    for (auto& [topic, s] : subscriptions_)
      while (s->reader->take(sample)) {
        server_.publish(s->channel, simulated_ns(sample.header.t), sample.cdr);
        samples_.fetch_add(1, std::memory_order_relaxed);
        took = true;
      }
    // Woken per sample, this thread would take a core's share from the run it watches; the
    // samples wait in the readers' history meanwhile (as the recorder's do: recorder.h).
    if (took) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace mechsim::live
