// The live server in process (tools/live/live_server.h) through a real WebSocket client on
// loopback: the Foxglove handshake and messages, subscription, decimation, a late client,
// a client that stops reading. No DDS: samples are published by the test.
#include "live_server.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>

#include "ws_test_client.h"

namespace mechsim::live {
namespace {

using nlohmann::json;
using testing::WsFrame;
using testing::WsTestClient;
using namespace std::chrono_literals;

std::string uri(const LiveServer& s) { return "ws://127.0.0.1:" + std::to_string(s.port()) + "/"; }

LiveOptions loopback(double rate_hz) {
  LiveOptions o;
  o.port = 0;
  o.rate_hz = rate_hz;
  o.name = "test server";
  o.metadata = {{"run_id", "0123"}};
  return o;
}

ChannelInfo channel(const std::string& topic) {
  ChannelInfo c;
  c.topic = topic;
  c.schema_name = "mechsim::msg::CamState";
  c.schema = "module mechsim { module msg { struct CamState { double angle; }; }; };";
  return c;
}

// Frames until `enough` says so or `timeout`.
std::vector<WsFrame> collect(WsTestClient& c, std::chrono::milliseconds timeout, const std::function<bool(const std::vector<WsFrame>&)>& enough) {
  std::vector<WsFrame> all;
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    for (auto& f : c.take()) all.push_back(std::move(f));
    if (enough(all)) break;
    std::this_thread::sleep_for(5ms);
  }
  return all;
}

struct Data {
  std::uint32_t subscription;
  std::uint64_t t_ns;
  std::string payload;
};
Data data_of(const WsFrame& f) {
  EXPECT_TRUE(f.binary);
  EXPECT_GE(f.data.size(), 13u);
  EXPECT_EQ(static_cast<unsigned char>(f.data[0]), 0x01);
  Data d{};
  std::memcpy(&d.subscription, f.data.data() + 1, 4);  // little endian, as this machine
  std::memcpy(&d.t_ns, f.data.data() + 5, 8);
  d.payload = f.data.substr(13);
  return d;
}

std::vector<std::byte> bytes(const std::string& s) {
  std::vector<std::byte> b(s.size());
  std::memcpy(b.data(), s.data(), s.size());
  return b;
}

TEST(LiveServer, HandshakeServerInfoAndAdvertise) {
  LiveServer server(loopback(60));
  server.add_channel(channel("cam/state"));
  WsTestClient c(uri(server), kSubprotocol, 5s);
  ASSERT_TRUE(c.opened());
  EXPECT_EQ(c.subprotocol(), "foxglove.websocket.v1");
  auto frames = collect(c, 5s, [](const auto& f) { return f.size() >= 2; });
  ASSERT_GE(frames.size(), 2u);
  const json info = json::parse(frames[0].data);
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "test server");
  EXPECT_EQ(info["metadata"]["run_id"], "0123");
  EXPECT_TRUE(info["capabilities"].empty());  // read-only: no publish, parameters, services
  const json adv = json::parse(frames[1].data);
  EXPECT_EQ(adv["op"], "advertise");
  ASSERT_EQ(adv["channels"].size(), 1u);
  const json& ch = adv["channels"][0];
  EXPECT_EQ(ch["id"], 1);
  EXPECT_EQ(ch["topic"], "cam/state");
  EXPECT_EQ(ch["encoding"], "cdr");
  EXPECT_EQ(ch["schemaName"], "mechsim::msg::CamState");
  EXPECT_EQ(ch["schemaEncoding"], "omgidl");
  EXPECT_NE(ch["schema"].get<std::string>().find("struct CamState"), std::string::npos);

  // A channel added later is advertised to the clients already there.
  server.add_channel(channel("follower/state"));
  frames = collect(c, 5s, [](const auto& f) { return !f.empty(); });
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(json::parse(frames[0].data)["channels"][0]["topic"], "follower/state");

  // Read-only: a client's publish request is answered with an error status.
  c.send_text(R"({"op":"advertise","channels":[]})");
  frames = collect(c, 5s, [](const auto& f) { return !f.empty(); });
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(json::parse(frames[0].data)["op"], "status");
  EXPECT_EQ(json::parse(frames[0].data)["level"], 2);
}

TEST(LiveServer, RefusesAClientWithoutTheSubprotocolAndBeyondTheLimit) {
  LiveOptions o = loopback(60);
  o.max_clients = 1;
  LiveServer server(o);
  WsTestClient none(uri(server), "", 5s);
  EXPECT_FALSE(none.opened());
  EXPECT_EQ(none.http_status(), 400);
  WsTestClient first(uri(server), kSubprotocol, 5s);
  ASSERT_TRUE(first.opened());
  WsTestClient second(uri(server), kSubprotocol, 5s);
  EXPECT_FALSE(second.opened());
  EXPECT_EQ(second.http_status(), 503);
}

// A 20 kHz source (1 ms steps, 20 simulated s per wall s) watched at 50 Hz for 1.5 s. The
// server sends a channel at most once per tick of 1/50 s, so a client gets at most
// 50 * wall + 1 messages in any window (+1: a window of whole ticks holds one tick more
// than its length when it starts on one); the latest value comes with the subscription.
TEST(LiveServer, DecimatesToTheRateAndChoosesEvenlyInSimulationTime) {
  const double rate = 50.0;
  LiveServer server(loopback(rate));
  const std::uint32_t id = server.add_channel(channel("cam/state"));
  server.publish(id, 7, bytes("first"));
  std::this_thread::sleep_for(100ms);  // sent at a tick to nobody: the subscription below gets it as the latest
  WsTestClient c(uri(server), kSubprotocol, 5s);
  ASSERT_TRUE(c.opened());
  collect(c, 5s, [](const auto& f) { return f.size() >= 2; });
  c.send_text(R"({"op":"subscribe","subscriptions":[{"id":42,"channelId":1}]})");
  auto frames = collect(c, 5s, [](const auto& f) { return !f.empty(); });
  ASSERT_FALSE(frames.empty());
  Data d = data_of(frames[0]);
  EXPECT_EQ(d.subscription, 42u);
  EXPECT_EQ(d.t_ns, 7u);  // the latest sample, at once
  EXPECT_EQ(d.payload, "first");

  std::atomic<bool> stop{false};
  std::uint64_t published = 0;
  std::thread source([&] {
    const auto start = std::chrono::steady_clock::now();
    std::uint64_t step = 1;
    while (!stop) {
      // 20 samples per wall ms.
      const auto due = start + std::chrono::microseconds(step * 50);
      std::this_thread::sleep_until(due);
      server.publish(id, step * 1'000'000, bytes("step " + std::to_string(step)));
      ++step;
    }
    published = step - 1;
  });
  const auto start = std::chrono::steady_clock::now();
  frames = collect(c, 1500ms, [](const auto&) { return false; });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stop = true;
  source.join();
  ASSERT_GT(published, 10000u);
  EXPECT_LE(static_cast<double>(frames.size()), rate * wall + 1) << frames.size() << " messages in " << wall << " s";
  // A loaded machine may miss ticks (the suite runs beside builds), not most of them.
  EXPECT_GE(static_cast<double>(frames.size()), 0.25 * rate * wall);
  std::vector<std::uint64_t> t;
  for (const auto& f : frames) {
    const Data x = data_of(f);
    EXPECT_EQ(x.payload, "step " + std::to_string(x.t_ns / 1'000'000));  // the bytes of that sample
    t.push_back(x.t_ns);
  }
  // Once the pace is measured (after a quarter second) consecutive samples are a stride
  // apart: 20 s/s / 50 Hz = 0.4 s of simulation at the source's nominal pace. The exact
  // rule is Decimator's test (a made-up clock); here, with real threads that a loaded
  // machine delays (the source's pace and the ticks both), the median gap is checked.
  std::vector<double> gaps;
  for (std::size_t i = t.size() / 2; i + 1 < t.size(); ++i) {
    EXPECT_GT(t[i + 1], t[i]);
    gaps.push_back((t[i + 1] - t[i]) * 1e-9);
  }
  ASSERT_GT(gaps.size(), 5u);
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  const double median = gaps[gaps.size() / 2];
  EXPECT_GT(median, 0.2) << "median gap " << median << " s";
  EXPECT_LT(median, 1.0) << "median gap " << median << " s";
}

// A client that stops reading is dropped once its unsent bytes pass the bound; publish()
// never waits for it, and another client keeps receiving.
TEST(LiveServer, DropsAClientThatStopsReadingAndNeverWaitsForIt) {
  LiveOptions o = loopback(1000);
  o.max_buffered_bytes = 1 << 20;
  LiveServer server(o);
  const std::uint32_t id = server.add_channel(channel("big"));
  WsTestClient slow(uri(server), kSubprotocol, 5s), reader(uri(server), kSubprotocol, 5s);
  ASSERT_TRUE(slow.opened() && reader.opened());
  for (WsTestClient* c : {&slow, &reader}) c->send_text(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})");
  std::this_thread::sleep_for(100ms);
  slow.stop_reading();
  const std::string payload(64 * 1024, 'x');
  const auto b = bytes(payload);
  double slowest_publish = 0;
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t step = 0;
  while (server.stats().clients_dropped == 0 && std::chrono::steady_clock::now() - start < 30s) {
    const auto before = std::chrono::steady_clock::now();
    server.publish(id, ++step * 1'000'000, b);
    slowest_publish = std::max(slowest_publish, std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count());
    std::this_thread::sleep_for(200us);
    reader.take();
  }
  EXPECT_EQ(server.stats().clients_dropped, 1u);
  // publish() copies into the channel's slot under a mutex the tick holds for as long as
  // it copies out one sample per channel: far below a 60 Hz frame even on a loaded machine.
  EXPECT_LT(slowest_publish, 0.05);
  // The reader still receives.
  auto frames = collect(reader, 5s, [](const auto& f) { return !f.empty(); });
  EXPECT_FALSE(frames.empty());
  EXPECT_TRUE(reader.opened() && !reader.closed());
}

TEST(LiveServer, ParsesListenAddresses) {
  LiveOptions o;
  parse_listen_address("9000", o);
  EXPECT_EQ(o.address, "127.0.0.1");
  EXPECT_EQ(o.port, 9000);
  parse_listen_address("0.0.0.0:8765", o);
  EXPECT_EQ(o.address, "0.0.0.0");
  EXPECT_EQ(o.port, 8765);
  parse_listen_address("[::1]:1234", o);
  EXPECT_EQ(o.address, "::1");
  EXPECT_THROW(parse_listen_address("port", o), std::invalid_argument);
  EXPECT_THROW(parse_listen_address("1.2.3.4:70000", o), std::invalid_argument);
  EXPECT_THROW(parse_listen_address(":80", o), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::live
