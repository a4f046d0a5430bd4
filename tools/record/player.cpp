#include "player.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <thread>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/transport/raw.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::recorder {

namespace {

using Clock = std::chrono::steady_clock;

struct Queued {
  std::uint64_t publish_time;  // simulated time [ns] (the recorder's convention)
  std::size_t order;           // position in the file: ties keep the recorded order
  std::size_t writer;
  std::vector<std::byte> cdr;
};

bool selected(const PlayOptions& o, const std::string& topic) {
  const bool infrastructure = topic == transport::kControlTopic || topic == transport::kStatusTopic;
  if (o.topics.all()) return !infrastructure;
  return o.topics.selects(topic);
}

}  // namespace

PlayReport play(int domain_id, const PlayOptions& options) {
  options.topics.validate();
  if (!(options.rate >= 0) || !std::isfinite(options.rate))
    throw std::invalid_argument("--rate: expected a factor >= 0 (0: as fast as possible), got " + std::to_string(options.rate));
  if (!(options.end_s > options.start_s)) throw std::invalid_argument("--end: expected a time after --start");

  record::McapReader reader(options.file);
  auto participant = transport::create_raw_participant(options.vendor, domain_id);
  std::map<std::uint16_t, std::size_t> writer_of_channel;
  std::vector<std::unique_ptr<transport::RawWriter>> writers;
  std::vector<std::string> writer_topics;
  for (const auto& [id, channel] : reader.channels()) {
    if (!selected(options, channel.topic) || channel.message_encoding != "cdr") continue;
    auto schema = reader.schemas().find(channel.schema_id);
    if (schema == reader.schemas().end() || transport::scoped_type_name(schema->second.name).empty()) continue;
    writer_of_channel[id] = writers.size();
    writers.push_back(participant->create_writer(channel.topic, schema->second.name));
    writer_topics.push_back(channel.topic);
  }
  if (writers.empty())
    throw std::runtime_error(options.file + ": no recorded mechsim topic matches the selection (`mechsim bag info " +
                             options.file + "` lists the topics)");

  std::vector<Queued> queue;
  const double ns = 1e9;
  reader.for_each_message([&](const record::MessageView& m) {
    auto w = writer_of_channel.find(m.channel_id);
    if (w == writer_of_channel.end()) return;
    const double t = static_cast<double>(m.publish_time) / ns;
    if (t < options.start_s - 1e-12 || t > options.end_s + 1e-12) return;
    queue.push_back({m.publish_time, queue.size(), w->second, {m.data.begin(), m.data.end()}});
  });
  std::stable_sort(queue.begin(), queue.end(), [](const Queued& a, const Queued& b) { return a.publish_time < b.publish_time; });
  if (queue.empty()) throw std::runtime_error(options.file + ": no sample of the selected topics in the time window");

  const auto should_stop = [&] { return options.stop && options.stop->load(); };
  const auto readers_deadline = Clock::now() + options.wait_for_readers;
  for (;;) {
    bool all = std::all_of(writers.begin(), writers.end(), [](const auto& w) { return w->matched_readers() > 0; });
    if (all || Clock::now() >= readers_deadline || should_stop()) break;
    participant->wait(std::chrono::milliseconds(10));
  }

  PlayReport report;
  const auto first = Clock::now();
  auto last_progress = first;
  do {
    const auto pass_start = Clock::now();
    const std::uint64_t t0 = queue.front().publish_time;
    for (const Queued& q : queue) {
      if (should_stop()) {
        report.stopped = true;
        break;
      }
      if (options.rate > 0) {
        const double due_s = static_cast<double>(q.publish_time - t0) / ns / options.rate;
        std::this_thread::sleep_until(pass_start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(due_s)));
      }
      writers[q.writer]->write(q.cdr);  // reliable keep-all: blocks while a reader lags
      ++report.published[writer_topics[q.writer]];
      ++report.total;
      if (options.progress && Clock::now() - last_progress > std::chrono::milliseconds(200)) {
        options.progress(static_cast<double>(q.publish_time) / ns, report.total);
        last_progress = Clock::now();
      }
    }
    if (!report.stopped) ++report.loops;
  } while (options.loop && !report.stopped);
  for (auto& w : writers) w->flush(std::chrono::seconds(5));  // delivered before the participant goes
  report.wall_time_s = std::chrono::duration<double>(Clock::now() - first).count();
  return report;
}

}  // namespace mechsim::recorder
