#include "bag_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <thread>
#include <vector>

#include "mechsim/record/mcap_reader.h"

namespace mechsim::live {

namespace {
using Clock = std::chrono::steady_clock;
struct Queued {
  std::uint64_t t_ns;
  std::uint32_t channel;
  std::vector<std::byte> cdr;
};
}  // namespace

BagServeReport serve_bag(LiveServer& server, const BagServeOptions& options) {
  if (!(options.rate > 0) || !std::isfinite(options.rate))
    throw std::invalid_argument("--rate: expected a factor > 0 of real time, got " + std::to_string(options.rate));
  record::McapReader reader(options.file);
  std::map<std::uint16_t, std::uint32_t> served_channel;  // file channel -> server channel
  for (const auto& [id, channel] : reader.channels()) {
    auto schema = reader.schemas().find(channel.schema_id);
    if (channel.message_encoding != "cdr" || schema == reader.schemas().end() || schema->second.encoding != "omgidl") continue;
    ChannelInfo info;
    info.topic = channel.topic;
    info.schema_name = schema->second.name;
    info.schema = schema->second.data;
    for (const auto& [key, value] : channel.metadata)
      if (key.starts_with("mechsim.")) info.metadata[key] = value;
    served_channel[id] = server.add_channel(std::move(info));
  }
  if (served_channel.empty())
    throw std::runtime_error(options.file + ": no CDR channel with an OMG IDL schema to serve (`mechsim bag info " + options.file + "`)");
  std::vector<Queued> queue;
  reader.for_each_message([&](const record::MessageView& m) {
    if (auto c = served_channel.find(m.channel_id); c != served_channel.end())
      queue.push_back({m.publish_time, c->second, {m.data.begin(), m.data.end()}});
  });
  std::stable_sort(queue.begin(), queue.end(), [](const Queued& a, const Queued& b) { return a.t_ns < b.t_ns; });

  BagServeReport report;
  report.channels = served_channel.size();
  const auto should_stop = [&] { return options.stop && options.stop->load(); };
  auto last_progress = Clock::now();
  while (!queue.empty()) {
    const auto pass_start = Clock::now();
    const std::uint64_t t0 = queue.front().t_ns;
    for (const Queued& q : queue) {
      if (should_stop()) {
        report.stopped = true;
        return report;
      }
      const double due_s = static_cast<double>(q.t_ns - t0) / 1e9 / options.rate;
      std::this_thread::sleep_until(pass_start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(due_s)));
      server.publish(q.channel, q.t_ns, q.cdr);
      ++report.served;
      if (options.progress && Clock::now() - last_progress > std::chrono::milliseconds(200)) {
        options.progress(static_cast<double>(q.t_ns) / 1e9, report.served);
        last_progress = Clock::now();
      }
    }
    ++report.loops;
    if (!options.loop) break;
  }
  return report;
}

}  // namespace mechsim::live
