// The live server (docs/live.md): the Foxglove WebSocket protocol on one port, fed with
// samples by whoever reads them (domain_source.h: a DDS domain; bag_source.h: a
// recording), and the browser page on the same port (live_page.h).
//
//   LiveServer server(options);                       // listens when this returns
//   auto id = server.add_channel({.topic = ..., .schema_name = ..., .schema = ...});
//   server.publish(id, t_ns, cdr);                    // from any thread, never blocks on a client
//
// Each channel goes through a Decimator (decimator.h): a client receives a channel at most
// options.rate_hz times a second, samples chosen evenly in simulation time, and a client
// that subscribes gets the channel's latest sample at once. Read-only: clients can
// subscribe and unsubscribe, nothing else.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "decimator.h"
#include "foxglove_protocol.h"
#include "ws_endpoint.h"

namespace mechsim::live {

struct LiveOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8765;  // Foxglove's default; 0: any free port
  double rate_hz = 60.0;      // per channel and client, at most
  std::size_t max_clients = 8;
  std::size_t max_buffered_bytes = std::size_t{4} << 20;  // per client, unsent; more: dropped
  std::string name = "mechsim";                           // serverInfo name
  std::map<std::string, std::string> metadata;            // serverInfo metadata (the run's identity)
  std::string session_id;
};

struct LiveStats {
  std::uint64_t clients_connected = 0;  // since the start
  std::uint64_t clients_dropped = 0;    // for not reading
  std::uint64_t messages_sent = 0;      // message-data frames, all clients
  std::uint64_t samples_offered = 0;    // publish() calls
};

// "PORT", "ADDRESS:PORT" or "[IPv6]:PORT" into options.address / options.port (the address
// stays loopback when not given). Throws std::invalid_argument saying what was expected.
void parse_listen_address(const std::string& text, LiveOptions& options);

class LiveServer {
 public:
  // Throws std::invalid_argument for a rate that is not positive, std::runtime_error when
  // the port cannot be had.
  explicit LiveServer(const LiveOptions& options);
  ~LiveServer();

  std::uint16_t port() const;
  const LiveOptions& options() const { return options_; }
  // Advertised to the connected clients at once, and to later ones on connection. The id
  // is assigned (info.id is ignored). Any thread.
  std::uint32_t add_channel(ChannelInfo info);
  void publish(std::uint32_t channel, std::uint64_t t_ns, std::span<const std::byte> cdr);
  LiveStats stats() const;

 private:
  struct Channel {
    ChannelInfo info;
    Decimator decimator;
  };
  struct Outgoing {
    std::uint32_t channel = 0;
    TimedSample sample;
  };
  using Subscriptions = std::map<std::uint32_t, std::uint32_t>;  // subscription id -> channel id

  // The endpoint's thread:
  void on_open(std::uint64_t client);
  void on_text(std::uint64_t client, const std::string& text);
  void on_tick();
  void send_sample(std::uint64_t client, std::uint32_t subscription, const TimedSample& sample);

  LiveOptions options_;
  mutable std::mutex mutex_;  // channels_ and the counters below
  std::vector<std::unique_ptr<Channel>> channels_;  // index = id - 1
  std::uint64_t offered_ = 0, sent_ = 0, connected_ = 0;
  // The endpoint's thread only:
  std::map<std::uint64_t, Subscriptions> clients_;
  std::vector<Outgoing> outgoing_;
  std::vector<std::byte> frame_;
  std::unique_ptr<WsEndpoint> endpoint_;  // last: its thread uses everything above
};

}  // namespace mechsim::live
