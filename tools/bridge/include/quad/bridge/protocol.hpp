// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The Foxglove WebSocket protocol (subprotocol foxglove.websocket.v1), the part quad's bridge
/// speaks: the server's JSON messages (serverInfo, advertise, status) and binary Message Data;
/// the client's subscribe, unsubscribe, advertise, unadvertise (JSON) and Client Message Data
/// (binary). No network and no DDS: text and bytes in, text and bytes out.

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace quad::bridge {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

/// A malformed client message; what() names the op and the field.
class ProtocolError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A channel the server advertises: a topic with its schema (OMG IDL text), messages in CDR.
struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string schema_name;  ///< "quad::msg::VehicleState", "foxglove::SceneUpdate"
  std::string schema;       ///< the IDL text
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

std::string serverInfo(const std::string& name, bool client_publish, const std::string& session_id);
std::string advertise(const std::vector<Channel>& channels);
std::string status(StatusLevel level, const std::string& message);

/// The 13 bytes before a Message Data payload: opcode 1, subscription id, timestamp [ns],
/// little endian.
using MessageHeader = std::array<std::uint8_t, 13>;
MessageHeader messageHeader(std::uint32_t subscription_id, std::uint64_t timestamp_ns);

struct Subscribe {
  struct Subscription {
    std::uint32_t id = 0;
    std::uint32_t channel_id = 0;
  };
  std::vector<Subscription> subscriptions;
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct ClientAdvertise {
  struct ClientChannel {
    std::uint32_t id = 0;
    std::string topic;
    std::string encoding;
    std::string schema_name;
  };
  std::vector<ClientChannel> channels;
};
struct ClientUnadvertise {
  std::vector<std::uint32_t> channel_ids;
};
/// An op the bridge does not serve (parameters, services, ...): answered with a status.
struct Unsupported {
  std::string op;
};
using ClientRequest = std::variant<Subscribe, Unsubscribe, ClientAdvertise, ClientUnadvertise, Unsupported>;

/// A client's JSON message; throws ProtocolError.
ClientRequest parseClientText(std::string_view text);

/// A client's binary message: Client Message Data (opcode 1), its channel and payload;
/// throws ProtocolError on another opcode or a short message.
struct ClientMessage {
  std::uint32_t channel_id = 0;
  std::span<const std::uint8_t> payload;
};
ClientMessage parseClientBinary(std::span<const std::uint8_t> bytes);

}  // namespace quad::bridge
