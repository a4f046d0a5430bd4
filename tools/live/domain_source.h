// Feeds a LiveServer from a DDS domain, reading as a tool: a raw Cyclone participant of its
// own whose readers carry the tool tag (transport/raw.h, kToolReaderUserData), so that no
// node counts them as a partner, and that takes every sample as it comes on a thread of
// its own (the data topics are reliable keep-all: a reader that fell behind would slow
// the writers; this one only copies the bytes into the channel's decimator). Topics are
// followed through discovery like the recorder's (recorder.h), and those given with
// their type get their reader at once.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "live_server.h"
#include "cdr_decoder.h"
#include "recorder.h"

namespace mechsim::transport {
class RawParticipant;
class RawReader;
}  // namespace mechsim::transport

namespace mechsim::live {

struct DomainSourceOptions {
  int domain = 0;
  recorder::TopicSelection topics;  // all mechsim topics by default
  std::map<std::string, std::string> topic_types;   // topic -> type: subscribed at once
  std::map<std::string, std::string> topic_fields;  // FmuOutputs topics: cdr_decoder.h fields_text
};

class DomainSource {
 public:
  // Throws std::invalid_argument for a bad selection or type, std::runtime_error when DDS
  // refuses.
  DomainSource(LiveServer& server, const DomainSourceOptions& options);
  ~DomainSource();
  // This source's readers by (topic, type): what a launcher leaves out when it counts the
  // readers its nodes must have matched before the start (the live server is not waited
  // for). Any thread.
  std::map<std::pair<std::string, std::string>, int> readers() const;
  std::uint64_t samples() const { return samples_.load(); }

 private:
  struct Subscription;
  void subscribe(const std::string& topic, const recorder::MessageLayout& layout);
  void run();

  LiveServer& server_;
  DomainSourceOptions options_;
  std::unique_ptr<transport::RawParticipant> participant_;
  mutable std::mutex mutex_;  // subscriptions_ (changed by the source thread only)
  std::map<std::string, std::unique_ptr<Subscription>> subscriptions_;
  std::atomic<std::uint64_t> samples_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace mechsim::live
