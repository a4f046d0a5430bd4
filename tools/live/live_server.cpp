#include "live_server.h"

#include <stdexcept>

#include "live_page.h"

namespace mechsim::live {

void parse_listen_address(const std::string& text, LiveOptions& options) {
  const auto colon = text.rfind(':');
  std::string port = text;
  if (colon != std::string::npos) {
    std::string address = text.substr(0, colon);
    if (address.size() >= 2 && address.front() == '[' && address.back() == ']') address = address.substr(1, address.size() - 2);
    if (address.empty()) throw std::invalid_argument("'" + text + "': expected PORT or ADDRESS:PORT, e.g. 8765 or 0.0.0.0:8765");
    options.address = address;
    port = text.substr(colon + 1);
  }
  std::size_t used = 0;
  long value = -1;
  try {
    value = std::stol(port, &used);
  } catch (const std::exception&) {
  }
  if (used != port.size() || value < 0 || value > 65535)
    throw std::invalid_argument("'" + text + "': expected a port 0..65535, as PORT or ADDRESS:PORT (e.g. 8765 or 0.0.0.0:8765)");
  options.port = static_cast<std::uint16_t>(value);
}

LiveServer::LiveServer(const LiveOptions& options) : options_(options) {
  if (!(options_.rate_hz > 0) || options_.rate_hz > 10000)
    throw std::invalid_argument("live rate: expected messages per second per channel, > 0 and <= 10000, got " +
                                std::to_string(options_.rate_hz));
  WsEndpointOptions w;
  w.address = options_.address;
  w.port = options_.port;
  w.subprotocol = kSubprotocol;
  w.max_clients = options_.max_clients;
  w.max_buffered_bytes = options_.max_buffered_bytes;
  w.tick_period = std::chrono::microseconds(static_cast<std::int64_t>(1e6 / options_.rate_hz));
  WsHandlers h;
  h.opened = [this](std::uint64_t client) { on_open(client); };
  h.text = [this](std::uint64_t client, const std::string& text) { on_text(client, text); };
  h.closed = [this](std::uint64_t client) { clients_.erase(client); };
  h.tick = [this] { on_tick(); };
  h.http = [](const std::string& path) { return page_reply(path); };
  endpoint_ = std::make_unique<WsEndpoint>(w, std::move(h));
}

LiveServer::~LiveServer() { endpoint_.reset(); }

std::uint16_t LiveServer::port() const { return endpoint_->port(); }

std::uint32_t LiveServer::add_channel(ChannelInfo info) {
  std::uint32_t id = 0;
  {
    std::lock_guard lock(mutex_);
    id = static_cast<std::uint32_t>(channels_.size() + 1);
    info.id = id;
    channels_.push_back(std::make_unique<Channel>(Channel{info, Decimator(options_.rate_hz)}));
  }
  endpoint_->post([this, info] {
    const std::string text = advertise_json({info});
    for (const auto& [client, subs] : clients_) endpoint_->send_text(client, text);
  });
  return id;
}

void LiveServer::publish(std::uint32_t channel, std::uint64_t t_ns, std::span<const std::byte> cdr) {
  std::lock_guard lock(mutex_);
  if (channel == 0 || channel > channels_.size()) return;
  channels_[channel - 1]->decimator.offer(t_ns, cdr);
  ++offered_;
}

LiveStats LiveServer::stats() const {
  std::lock_guard lock(mutex_);
  return {connected_, endpoint_->dropped_clients(), sent_, offered_};
}

void LiveServer::on_open(std::uint64_t client) {
  clients_[client] = {};
  endpoint_->send_text(client, server_info_json(options_.name, options_.metadata, options_.session_id));
  std::vector<ChannelInfo> infos;
  {
    std::lock_guard lock(mutex_);
    ++connected_;
    for (const auto& c : channels_) infos.push_back(c->info);
  }
  if (!infos.empty()) endpoint_->send_text(client, advertise_json(infos));
}

void LiveServer::on_text(std::uint64_t client, const std::string& text) {
  const ClientRequest request = parse_client_request(text);
  if (const auto* s = std::get_if<Subscribe>(&request)) {
    for (const auto& [subscription, channel] : s->subscriptions) {
      TimedSample latest;
      bool known = false;
      {
        std::lock_guard lock(mutex_);
        known = channel >= 1 && channel <= channels_.size();
        if (known) latest = channels_[channel - 1]->decimator.latest();
      }
      if (!known) {
        endpoint_->send_text(client, status_json(1, "no channel " + std::to_string(channel)));
        continue;
      }
      auto it = clients_.find(client);
      if (it == clients_.end()) return;  // dropped meanwhile
      it->second[subscription] = channel;
      // A late client sees the latest value at once, not only at the channel's next sample.
      if (latest.valid) send_sample(client, subscription, latest);
    }
  } else if (const auto* u = std::get_if<Unsubscribe>(&request)) {
    if (auto it = clients_.find(client); it != clients_.end())
      for (std::uint32_t id : u->subscription_ids) it->second.erase(id);
  } else {
    const std::string& op = std::get<OtherRequest>(request).op;
    endpoint_->send_text(client, status_json(2, op.empty() ? "not a request of foxglove.websocket.v1"
                                                           : "this server is read-only: '" + op + "' is not supported"));
  }
}

void LiveServer::send_sample(std::uint64_t client, std::uint32_t subscription, const TimedSample& sample) {
  message_data_frame(subscription, sample.t_ns, sample.cdr, frame_);
  if (endpoint_->send_binary(client, frame_.data(), frame_.size())) {
    std::lock_guard lock(mutex_);
    ++sent_;
  }
}

void LiveServer::on_tick() {
  std::size_t n = 0;
  {
    std::lock_guard lock(mutex_);
    const auto now = Decimator::Clock::now();
    // The decimators run whether or not anyone watches: a client that comes sees the
    // same choice of samples as one that was there.
    for (const auto& c : channels_) {
      if (outgoing_.size() <= n) outgoing_.resize(n + 1);
      if (c->decimator.due(now, outgoing_[n].sample)) outgoing_[n++].channel = c->info.id;
    }
  }
  if (clients_.empty()) return;
  // Copies: send_binary may drop a client, which erases it from clients_.
  std::vector<std::pair<std::uint64_t, Subscriptions>> clients(clients_.begin(), clients_.end());
  for (const auto& [client, subs] : clients)
    for (const auto& [subscription, channel] : subs)
      for (std::size_t i = 0; i < n; ++i)
        if (outgoing_[i].channel == channel && clients_.count(client)) send_sample(client, subscription, outgoing_[i].sample);
}

}  // namespace mechsim::live
