// A WebSocket client for the live server's tests (websocketpp over standalone asio, like the
// server; C++17 for the same reason: tools/live/ws_endpoint.h). It records every frame it
// receives; stop_reading() makes it a client that no longer reads its socket, so the
// server's unsent bytes for it grow.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mechsim::testing {

struct WsFrame {
  bool binary = false;
  std::string data;
  std::chrono::steady_clock::time_point received;
};

class WsTestClient {
 public:
  // Connects to ws://host:port/ asking for `subprotocol` ("" asks for none); waits up to
  // `timeout` for the handshake. opened() tells whether it succeeded.
  WsTestClient(const std::string& uri, const std::string& subprotocol, std::chrono::milliseconds timeout);
  ~WsTestClient();
  bool opened() const;
  bool closed() const;            // closed by the server (or failed)
  std::string subprotocol() const;  // as the server selected it
  int http_status() const;          // of the handshake response (101 when it opened)
  void send_text(const std::string& text);
  void stop_reading();
  // Frames received so far (and forgotten here).
  std::vector<WsFrame> take();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mechsim::testing
