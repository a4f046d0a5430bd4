// Feeds a LiveServer from an MCAP recording (`mechsim bag serve`): every CDR channel of a
// known schema, with the schema and metadata the file carries, its messages in
// simulation-time order paced to the wall clock at `rate` times real time.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "live_server.h"

namespace mechsim::live {

struct BagServeOptions {
  std::string file;
  double rate = 1.0;  // x real time, > 0
  bool loop = false;
  const std::atomic<bool>* stop = nullptr;
  std::function<void(double t_s, std::uint64_t served)> progress;  // about every 0.2 s
};

struct BagServeReport {
  std::size_t channels = 0;
  std::uint64_t served = 0;  // messages handed to the server (before decimation), all passes
  int loops = 0;
  bool stopped = false;
};

// Reads the file, adds its channels to `server` and paces its messages until the end (or
// `stop`). Throws std::runtime_error naming the file when it cannot be read or holds no
// channel to serve, std::invalid_argument for a rate that is not positive.
BagServeReport serve_bag(LiveServer& server, const BagServeOptions& options);

}  // namespace mechsim::live
