#include "foxglove_protocol.h"

#include <cstring>

#include <nlohmann/json.hpp>

namespace mechsim::live {

using nlohmann::json;

std::string server_info_json(const std::string& name, const std::map<std::string, std::string>& metadata,
                             const std::string& session_id) {
  // No capabilities: no client publishing, parameters, services or time messages.
  return json{{"op", "serverInfo"},     {"name", name},         {"capabilities", json::array()},
              {"supportedEncodings", json::array()}, {"metadata", metadata}, {"sessionId", session_id}}
      .dump();
}

std::string advertise_json(const std::vector<ChannelInfo>& channels) {
  json list = json::array();
  for (const auto& c : channels) {
    json j{{"id", c.id},         {"topic", c.topic},   {"encoding", c.encoding},
           {"schemaName", c.schema_name}, {"schema", c.schema}, {"schemaEncoding", c.schema_encoding}};
    for (const auto& [key, value] : c.metadata) j[key] = value;
    list.push_back(std::move(j));
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string status_json(int level, const std::string& message) {
  return json{{"op", "status"}, {"level", level}, {"message", message}}.dump();
}

void message_data_frame(std::uint32_t subscription, std::uint64_t timestamp_ns, std::span<const std::byte> payload,
                        std::vector<std::byte>& out) {
  out.resize(1 + 4 + 8 + payload.size());
  out[0] = std::byte{0x01};
  for (int i = 0; i < 4; ++i) out[1 + i] = static_cast<std::byte>((subscription >> (8 * i)) & 0xff);
  for (int i = 0; i < 8; ++i) out[5 + i] = static_cast<std::byte>((timestamp_ns >> (8 * i)) & 0xff);
  if (!payload.empty()) std::memcpy(out.data() + 13, payload.data(), payload.size());
}

ClientRequest parse_client_request(const std::string& text) {
  const json j = json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) return OtherRequest{};
  const std::string op = j["op"];
  try {
    if (op == "subscribe") {
      Subscribe s;
      for (const auto& e : j.at("subscriptions")) s.subscriptions.emplace_back(e.at("id").get<std::uint32_t>(), e.at("channelId").get<std::uint32_t>());
      return s;
    }
    if (op == "unsubscribe") {
      Unsubscribe u;
      for (const auto& e : j.at("subscriptionIds")) u.subscription_ids.push_back(e.get<std::uint32_t>());
      return u;
    }
  } catch (const json::exception&) {
    return OtherRequest{};
  }
  return OtherRequest{op};
}

}  // namespace mechsim::live
