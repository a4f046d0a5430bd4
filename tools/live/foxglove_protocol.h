// The Foxglove WebSocket protocol, server side (subprotocol "foxglove.websocket.v1",
// https://github.com/foxglove/ws-protocol): the JSON messages a
// server sends (serverInfo, advertise, unadvertise, status), the binary message-data frame,
// and the client requests a read-only server answers (subscribe, unsubscribe).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace mechsim::live {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

struct ChannelInfo {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding = "cdr";
  std::string schema_name;      // e.g. "mechsim::msg::CamState"
  std::string schema;           // the OMG IDL text a recording carries for it
  std::string schema_encoding = "omgidl";
  // Extra members of the channel object, e.g. "mechsim.fields" of an FMU participant's
  // topic (clients ignore members they do not know).
  std::map<std::string, std::string> metadata;
};

std::string server_info_json(const std::string& name, const std::map<std::string, std::string>& metadata,
                             const std::string& session_id);
std::string advertise_json(const std::vector<ChannelInfo>& channels);
// level 0 info, 1 warning, 2 error.
std::string status_json(int level, const std::string& message);

// Opcode 0x01, subscription id (uint32 LE), timestamp [ns] (uint64 LE), payload: into `out`
// (reused).
void message_data_frame(std::uint32_t subscription, std::uint64_t timestamp_ns, std::span<const std::byte> payload,
                        std::vector<std::byte>& out);

struct Subscribe {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  // (subscription id, channel id)
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct OtherRequest {
  std::string op;  // what a read-only server does not do ("" when the text is not a request)
};
using ClientRequest = std::variant<Subscribe, Unsubscribe, OtherRequest>;
// Never throws: malformed text gives OtherRequest{""}.
ClientRequest parse_client_request(const std::string& text);

}  // namespace mechsim::live
