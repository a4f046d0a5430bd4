// live_watch LOG_FILE [SECONDS]: a Foxglove WebSocket client for tools/bench-live.sh. Waits
// for a live server's "ws://127.0.0.1:PORT" line in LOG_FILE (a launcher's output), connects,
// subscribes to every channel as it is advertised and reads until the server closes (or
// SECONDS pass); prints {"messages": N, "channels": C} as JSON.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <thread>

#include "ws_test_client.h"

int main(int argc, char** argv) {
  using namespace std::chrono_literals;
  if (argc < 2) {
    std::fprintf(stderr, "usage: live_watch LOG_FILE [SECONDS]\n");
    return 2;
  }
  const double limit_s = argc > 2 ? std::stod(argv[2]) : 600;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::string port;
  while (port.empty() && elapsed() < limit_s) {
    std::ifstream in(argv[1]);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::smatch m;
    if (std::regex_search(text, m, std::regex("ws://127\\.0\\.0\\.1:([0-9]+)"))) port = m[1];
    else std::this_thread::sleep_for(2ms);
  }
  if (port.empty()) return 1;
  mechsim::testing::WsTestClient client("ws://127.0.0.1:" + port + "/", "foxglove.websocket.v1", 5s);
  if (!client.opened()) return 1;
  std::set<long> subscribed;
  long messages = 0;
  while (!client.closed() && elapsed() < limit_s) {
    for (const auto& f : client.take()) {
      if (f.binary) {
        ++messages;
        continue;
      }
      const auto j = nlohmann::json::parse(f.data);
      if (j["op"] != "advertise") continue;
      nlohmann::json subs = nlohmann::json::array();
      for (const auto& ch : j["channels"])
        if (subscribed.insert(ch["id"].get<long>()).second) subs.push_back({{"id", ch["id"]}, {"channelId", ch["id"]}});
      client.send_text(nlohmann::json{{"op", "subscribe"}, {"subscriptions", subs}}.dump());
    }
    std::this_thread::sleep_for(5ms);
  }
  std::printf("%s\n", nlohmann::json{{"messages", messages}, {"channels", subscribed.size()}}.dump().c_str());
  return 0;
}
