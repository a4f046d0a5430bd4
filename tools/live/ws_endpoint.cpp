// C++17 (see ws_endpoint.h): the only file that includes websocketpp (ASIO_STANDALONE: CMakeLists.txt).
#include "ws_endpoint.h"

#include <atomic>
#include <map>
#include <stdexcept>
#include <thread>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

namespace mechsim::live {

namespace {
using Server = websocketpp::server<websocketpp::config::asio>;
using ConnectionPtr = Server::connection_ptr;
}  // namespace

struct WsEndpoint::Impl {
  WsEndpointOptions options;
  WsHandlers handlers;
  Server server;
  std::unique_ptr<asio::steady_timer> timer;
  std::map<std::uint64_t, ConnectionPtr> clients;     // open WebSocket connections
  std::map<const void*, std::uint64_t> id_of;         // connection -> client id
  std::uint64_t next_id = 1;
  std::uint16_t port = 0;
  bool stopping = false;
  std::atomic<std::uint64_t> dropped{0};
  std::atomic<bool> ran_out{false};  // run() returned: no connection, no timer left
  std::thread thread;

  std::uint64_t id(websocketpp::connection_hdl hdl) {
    auto con = server.get_con_from_hdl(hdl);
    auto it = id_of.find(con.get());
    return it == id_of.end() ? 0 : it->second;
  }

  void arm_timer() {
    timer->expires_after(options.tick_period);
    timer->async_wait([this](const asio::error_code& ec) {
      if (ec || stopping) return;
      if (handlers.tick) handlers.tick();
      arm_timer();
    });
  }

  bool send(std::uint64_t client, const void* data, std::size_t size, websocketpp::frame::opcode::value op) {
    auto it = clients.find(client);
    if (it == clients.end()) return false;
    if (it->second->get_buffered_amount() + size > options.max_buffered_bytes) {
      dropped.fetch_add(1);
      close(client, "the client does not read fast enough: dropped");
      return false;
    }
    const auto ec = it->second->send(data, size, op);
    return !ec;
  }

  // Starts the closing handshake; the connection counts as gone at once.
  void close(std::uint64_t client, const std::string& reason) {
    auto it = clients.find(client);
    if (it == clients.end()) return;
    ConnectionPtr con = it->second;
    clients.erase(it);
    id_of.erase(con.get());
    websocketpp::lib::error_code ec;
    con->close(websocketpp::close::status::policy_violation, reason, ec);
    if (handlers.closed) handlers.closed(client);
  }

  void gone(websocketpp::connection_hdl hdl) {
    const std::uint64_t client = id(hdl);
    if (client == 0) return;  // closed by us already
    auto con = server.get_con_from_hdl(hdl);
    clients.erase(client);
    id_of.erase(con.get());
    if (handlers.closed) handlers.closed(client);
  }
};

WsEndpoint::WsEndpoint(const WsEndpointOptions& options, WsHandlers handlers) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  m.handlers = std::move(handlers);
  m.server.clear_access_channels(websocketpp::log::alevel::all);
  m.server.clear_error_channels(websocketpp::log::elevel::all);
  m.server.init_asio();
  m.server.set_reuse_addr(true);
  // A peer that never answers the closing handshake (one that stopped reading) is cut after this.
  m.server.set_close_handshake_timeout(1000);
  m.server.set_open_handshake_timeout(5000);
  m.server.set_max_message_size(1 << 16);  // subscribe requests, nothing large
  m.server.set_validate_handler([&m](websocketpp::connection_hdl hdl) {
    auto con = m.server.get_con_from_hdl(hdl);
    if (m.clients.size() >= m.options.max_clients) {
      con->set_status(websocketpp::http::status_code::service_unavailable);
      return false;
    }
    if (m.options.subprotocol.empty()) return true;
    for (const auto& p : con->get_requested_subprotocols())
      if (p == m.options.subprotocol) {
        con->select_subprotocol(p);
        return true;
      }
    con->set_status(websocketpp::http::status_code::bad_request);
    return false;
  });
  m.server.set_open_handler([&m](websocketpp::connection_hdl hdl) {
    auto con = m.server.get_con_from_hdl(hdl);
    const std::uint64_t client = m.next_id++;
    m.clients[client] = con;
    m.id_of[con.get()] = client;
    if (m.handlers.opened) m.handlers.opened(client);
  });
  m.server.set_close_handler([&m](websocketpp::connection_hdl hdl) { m.gone(hdl); });
  m.server.set_fail_handler([&m](websocketpp::connection_hdl hdl) { m.gone(hdl); });
  m.server.set_message_handler([&m](websocketpp::connection_hdl hdl, Server::message_ptr msg) {
    const std::uint64_t client = m.id(hdl);
    if (client != 0 && msg->get_opcode() == websocketpp::frame::opcode::text && m.handlers.text)
      m.handlers.text(client, msg->get_payload());
  });
  m.server.set_http_handler([&m](websocketpp::connection_hdl hdl) {
    auto con = m.server.get_con_from_hdl(hdl);
    HttpReply reply;
    if (con->get_request().get_method() != "GET") {
      reply = {405, "text/plain; charset=utf-8", "only GET\n"};
    } else if (m.handlers.http) {
      reply = m.handlers.http(con->get_resource());
    }
    con->set_status(static_cast<websocketpp::http::status_code::value>(reply.status));
    con->replace_header("Content-Type", reply.content_type);
    con->replace_header("Cache-Control", "no-store");
    con->set_body(reply.body);
  });

  asio::error_code ec;
  const auto address = asio::ip::make_address(options.address, ec);
  if (ec) throw std::runtime_error("'" + options.address + "' is not an IP address");
  websocketpp::lib::error_code wec;
  m.server.listen(asio::ip::tcp::endpoint(address, options.port), wec);
  if (wec) throw std::runtime_error("cannot listen on " + options.address + ":" + std::to_string(options.port) + ": " + wec.message());
  m.server.start_accept(wec);
  if (wec) throw std::runtime_error("cannot accept on " + options.address + ":" + std::to_string(options.port) + ": " + wec.message());
  m.port = m.server.get_local_endpoint(ec).port();
  m.timer = std::make_unique<asio::steady_timer>(m.server.get_io_service());
  m.arm_timer();
  m.thread = std::thread([&m] {
    m.server.run();
    m.ran_out = true;
  });
}

WsEndpoint::~WsEndpoint() {
  Impl& m = *impl_;
  m.server.get_io_service().post([&m] {
    m.stopping = true;
    m.timer->cancel();
    websocketpp::lib::error_code ec;
    m.server.stop_listening(ec);
    std::map<std::uint64_t, ConnectionPtr> open;
    open.swap(m.clients);
    m.id_of.clear();
    for (auto& [id, con] : open) con->close(websocketpp::close::status::going_away, "server stopping", ec);
  });
  // The closing handshakes take a round trip; a client that does not answer is not waited
  // for beyond the handshake timeout.
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1500);
  while (!m.ran_out && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  m.server.stop();
  if (m.thread.joinable()) m.thread.join();
}

std::uint16_t WsEndpoint::port() const { return impl_->port; }
bool WsEndpoint::send_text(std::uint64_t client, const std::string& text) {
  return impl_->send(client, text.data(), text.size(), websocketpp::frame::opcode::text);
}
bool WsEndpoint::send_binary(std::uint64_t client, const void* data, std::size_t size) {
  return impl_->send(client, data, size, websocketpp::frame::opcode::binary);
}
void WsEndpoint::drop(std::uint64_t client, const std::string& reason) { impl_->close(client, reason); }
void WsEndpoint::post(std::function<void()> task) { impl_->server.get_io_service().post(std::move(task)); }
std::uint64_t WsEndpoint::dropped_clients() const { return impl_->dropped.load(); }

}  // namespace mechsim::live
