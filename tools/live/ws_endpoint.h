// A WebSocket and HTTP server on one TCP port (websocketpp over standalone asio), for the
// live server (live_server.h). It knows nothing of Foxglove or DDS: connections, text and
// binary frames, an HTTP reply per GET, and a periodic tick, all on one thread of its own.
//
// This header and ws_endpoint.cpp are C++17: websocketpp 0.8 (Debian 12) does not compile
// as C++20, so its headers stay inside that one file.
//
// Every handler runs on the endpoint's thread; send_* and drop may be called only from a
// handler (or a function given to post). A client whose unsent bytes would pass
// max_buffered_bytes is dropped instead of waited for: a viewer that stops reading never
// holds up the server, nor what feeds it.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace mechsim::live {

struct HttpReply {
  int status = 404;
  std::string content_type = "text/plain; charset=utf-8";
  std::string body = "not found\n";
};

struct WsEndpointOptions {
  std::string address = "127.0.0.1";  // loopback unless the user gives another
  std::uint16_t port = 0;             // 0: any free port (port() tells which)
  std::string subprotocol;            // required of every WebSocket client ("" accepts any)
  std::size_t max_clients = 8;        // further WebSocket clients are refused (HTTP 503)
  std::size_t max_buffered_bytes = std::size_t{4} << 20;
  std::chrono::microseconds tick_period{16667};
};

struct WsHandlers {
  std::function<void(std::uint64_t client)> opened;
  std::function<void(std::uint64_t client, const std::string& text)> text;
  std::function<void(std::uint64_t client)> closed;  // also after drop()
  std::function<void()> tick;
  std::function<HttpReply(const std::string& path)> http;
};

class WsEndpoint {
 public:
  // Binds and listens before it returns; throws std::runtime_error naming the address when
  // the port cannot be had.
  WsEndpoint(const WsEndpointOptions& options, WsHandlers handlers);
  ~WsEndpoint();  // closes every connection and stops the thread
  WsEndpoint(const WsEndpoint&) = delete;
  WsEndpoint& operator=(const WsEndpoint&) = delete;

  std::uint16_t port() const;
  // False when the client is gone or was dropped now for being too slow.
  bool send_text(std::uint64_t client, const std::string& text);
  bool send_binary(std::uint64_t client, const void* data, std::size_t size);
  void drop(std::uint64_t client, const std::string& reason);
  // Runs `task` on the endpoint's thread (safe from any thread).
  void post(std::function<void()> task);
  // Clients dropped for not reading (any thread).
  std::uint64_t dropped_clients() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mechsim::live
