#include "ws_test_client.h"

#include <atomic>
#include <mutex>
#include <thread>

#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

namespace mechsim::testing {

using Client = websocketpp::client<websocketpp::config::asio_client>;

struct WsTestClient::Impl {
  Client client;
  Client::connection_ptr con;
  std::thread thread;
  mutable std::mutex mutex;
  std::vector<WsFrame> frames;
  std::atomic<bool> open{false}, done{false};
  std::string subprotocol;
  int status = 0;
};

WsTestClient::WsTestClient(const std::string& uri, const std::string& subprotocol, std::chrono::milliseconds timeout)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.client.clear_access_channels(websocketpp::log::alevel::all);
  m.client.clear_error_channels(websocketpp::log::elevel::all);
  m.client.init_asio();
  m.client.set_open_handler([&m](websocketpp::connection_hdl hdl) {
    auto con = m.client.get_con_from_hdl(hdl);
    std::lock_guard lock(m.mutex);
    // websocketpp's client does not keep the server's choice: the response header has it.
    m.subprotocol = con->get_response_header("Sec-WebSocket-Protocol");
    m.status = con->get_response_code();
    m.open = true;
  });
  m.client.set_fail_handler([&m](websocketpp::connection_hdl hdl) {
    auto con = m.client.get_con_from_hdl(hdl);
    std::lock_guard lock(m.mutex);
    m.status = con->get_response_code();
    m.done = true;
  });
  m.client.set_close_handler([&m](websocketpp::connection_hdl) { m.done = true; });
  m.client.set_message_handler([&m](websocketpp::connection_hdl, Client::message_ptr msg) {
    std::lock_guard lock(m.mutex);
    m.frames.push_back({msg->get_opcode() == websocketpp::frame::opcode::binary, msg->get_payload(), std::chrono::steady_clock::now()});
  });
  websocketpp::lib::error_code ec;
  m.con = m.client.get_connection(uri, ec);
  if (ec) {
    m.done = true;
    return;
  }
  if (!subprotocol.empty()) m.con->add_subprotocol(subprotocol);
  m.client.connect(m.con);
  m.thread = std::thread([&m] { m.client.run(); });
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!m.open && !m.done && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

WsTestClient::~WsTestClient() {
  Impl& m = *impl_;
  if (!m.thread.joinable()) return;
  m.client.get_io_service().post([&m] {
    websocketpp::lib::error_code ec;
    if (m.open && !m.done) m.con->close(websocketpp::close::status::normal, "done", ec);
  });
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  while (!m.done && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  m.client.stop();
  m.thread.join();
}

bool WsTestClient::opened() const { return impl_->open; }
bool WsTestClient::closed() const { return impl_->done; }
std::string WsTestClient::subprotocol() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->subprotocol;
}
int WsTestClient::http_status() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->status;
}
void WsTestClient::send_text(const std::string& text) {
  Impl& m = *impl_;
  m.client.get_io_service().post([&m, text] {
    m.con->send(text, websocketpp::frame::opcode::text);
  });
}
void WsTestClient::stop_reading() {
  Impl& m = *impl_;
  m.client.get_io_service().post([&m] { m.con->pause_reading(); });
}
std::vector<WsFrame> WsTestClient::take() {
  std::lock_guard lock(impl_->mutex);
  std::vector<WsFrame> out;
  out.swap(impl_->frames);
  return out;
}

}  // namespace mechsim::testing
