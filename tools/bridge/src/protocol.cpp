// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bridge/protocol.hpp"

#include <nlohmann/json.hpp>

namespace quad::bridge {

using Json = nlohmann::json;

std::string serverInfo(const std::string& name, bool client_publish, const std::string& session_id)
{
  Json j{{"op", "serverInfo"}, {"name", name}, {"capabilities", Json::array()}, {"sessionId", session_id},
         {"metadata", Json::object()}};
  if (client_publish) {
    j["capabilities"].push_back("clientPublish");
    j["supportedEncodings"] = Json::array({"cdr"});
  }
  return j.dump();
}

std::string advertise(const std::vector<Channel>& channels)
{
  Json list = Json::array();
  for (const auto& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", "cdr"},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", "omgidl"}});
  }
  return Json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string status(StatusLevel level, const std::string& message)
{
  return Json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump();
}

MessageHeader messageHeader(std::uint32_t subscription_id, std::uint64_t timestamp_ns)
{
  MessageHeader h{};
  h[0] = 0x01;
  for (int i = 0; i < 4; ++i) {
    h[static_cast<std::size_t>(1 + i)] = static_cast<std::uint8_t>(subscription_id >> (8 * i));
  }
  for (int i = 0; i < 8; ++i) {
    h[static_cast<std::size_t>(5 + i)] = static_cast<std::uint8_t>(timestamp_ns >> (8 * i));
  }
  return h;
}

namespace {

const Json& member(const Json& j, const char* key, const std::string& op)
{
  const auto it = j.find(key);
  if (it == j.end()) {
    throw ProtocolError(op + ": no '" + key + "'");
  }
  return *it;
}

std::uint32_t id(const Json& j, const char* key, const std::string& op)
{
  const Json& v = member(j, key, op);
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0xffffffffU) {
    throw ProtocolError(op + ": '" + key + "' is " + v.dump() + ", not a 32-bit unsigned number");
  }
  return v.get<std::uint32_t>();
}

std::string text(const Json& j, const char* key, const std::string& op)
{
  const Json& v = member(j, key, op);
  if (!v.is_string()) {
    throw ProtocolError(op + ": '" + key + "' is " + v.dump() + ", not a string");
  }
  return v.get<std::string>();
}

const Json& array(const Json& j, const char* key, const std::string& op)
{
  const Json& v = member(j, key, op);
  if (!v.is_array()) {
    throw ProtocolError(op + ": '" + key + "' is not an array");
  }
  return v;
}

std::vector<std::uint32_t> ids(const Json& j, const char* key, const std::string& op)
{
  std::vector<std::uint32_t> out;
  for (const auto& v : array(j, key, op)) {
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0xffffffffU) {
      throw ProtocolError(op + ": '" + key + "' holds " + v.dump() + ", not a 32-bit unsigned number");
    }
    out.push_back(v.get<std::uint32_t>());
  }
  return out;
}

}  // namespace

ClientRequest parseClientText(std::string_view message)
{
  const Json j = Json::parse(message, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    throw ProtocolError("a text message that is not a JSON object");
  }
  const std::string op = text(j, "op", "message");
  if (op == "subscribe") {
    Subscribe s;
    for (const auto& e : array(j, "subscriptions", op)) {
      s.subscriptions.push_back({id(e, "id", op), id(e, "channelId", op)});
    }
    return s;
  }
  if (op == "unsubscribe") {
    return Unsubscribe{ids(j, "subscriptionIds", op)};
  }
  if (op == "advertise") {
    ClientAdvertise a;
    for (const auto& e : array(j, "channels", op)) {
      a.channels.push_back({id(e, "id", op), text(e, "topic", op), text(e, "encoding", op), text(e, "schemaName", op)});
    }
    return a;
  }
  if (op == "unadvertise") {
    return ClientUnadvertise{ids(j, "channelIds", op)};
  }
  return Unsupported{op};
}

ClientMessage parseClientBinary(std::span<const std::uint8_t> bytes)
{
  if (bytes.empty() || bytes[0] != 0x01) {
    throw ProtocolError(bytes.empty() ? "an empty binary message"
                                      : "binary opcode " + std::to_string(bytes[0]) + " (only 1, message data, is served)");
  }
  if (bytes.size() < 5) {
    throw ProtocolError("client message data of " + std::to_string(bytes.size()) + " bytes: no channel id");
  }
  std::uint32_t channel = 0;
  for (int i = 0; i < 4; ++i) {
    channel |= static_cast<std::uint32_t>(bytes[static_cast<std::size_t>(1 + i)]) << (8 * i);
  }
  return {channel, bytes.subspan(5)};
}

}  // namespace quad::bridge
