// `mechsim play`: publishes the topics of an MCAP recording again on a DDS domain, as the
// CDR bytes that were recorded (docs/recording.md). Samples go out in simulated-time
// order, paced to the wall clock (`rate` times real time) or as fast as the readers take
// them (rate 0); a time window and a topic selection narrow what is played; `loop` starts
// over at the end. The samples keep their recorded run id and steps: tools (topic echo,
// another recorder, a user's own subscriber) see the run as it was. To stand in for a
// participant inside a live run, use `mechsim launch --replay NODE=FILE` instead: that
// replay is driven by the lock-step protocol, this one by the clock.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>

#include "recorder.h"

namespace mechsim::recorder {

struct PlayOptions {
  std::string file;
  // Which recorded topics to publish. With none named, every data topic: the control and
  // status topics are played only when named (a replayed `start` would drive live nodes).
  TopicSelection topics;
  double start_s = -std::numeric_limits<double>::infinity();  // simulated-time window
  double end_s = std::numeric_limits<double>::infinity();
  double rate = 1.0;  // x real time; 0 = unpaced
  bool loop = false;
  // Before the first sample: wait up to this long for every writer to see a reader (a
  // reliable sample written before a reader exists is not delivered to it).
  std::chrono::milliseconds wait_for_readers{2000};
  std::string vendor = "cyclone";
  const std::atomic<bool>* stop = nullptr;  // set from a signal handler to end early
  std::function<void(double t_s, std::uint64_t published)> progress;  // about every 0.2 s
};

struct PlayReport {
  std::map<std::string, std::uint64_t> published;  // per topic, all loops
  std::uint64_t total = 0;
  int loops = 0;           // passes completed
  double wall_time_s = 0;  // first to last sample
  bool stopped = false;    // ended by `stop`
};

// Throws std::runtime_error naming the file when it cannot be read or nothing is selected,
// std::invalid_argument for bad options.
PlayReport play(int domain_id, const PlayOptions& options);

}  // namespace mechsim::recorder
