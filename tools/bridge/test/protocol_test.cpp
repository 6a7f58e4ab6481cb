// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bridge/protocol.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace quad::bridge {
namespace {

using Json = nlohmann::json;

TEST(BridgeProtocol, ServerMessagesCarryTheSpecsFields)
{
  const Json info = Json::parse(serverInfo("quad bridge", true, "42"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["capabilities"], Json::array({"clientPublish"}));
  EXPECT_EQ(info["supportedEncodings"], Json::array({"cdr"}));
  EXPECT_EQ(info["sessionId"], "42");
  EXPECT_FALSE(Json::parse(serverInfo("x", false, "1")).contains("supportedEncodings"));

  const Json ad = Json::parse(advertise({{7, "quad/sim/state", "quad::msg::VehicleState", "struct VehicleState {};"}}));
  ASSERT_EQ(ad["channels"].size(), 1U);
  const Json& c = ad["channels"][0];
  EXPECT_EQ(c["id"], 7);
  EXPECT_EQ(c["topic"], "quad/sim/state");
  EXPECT_EQ(c["encoding"], "cdr");
  EXPECT_EQ(c["schemaName"], "quad::msg::VehicleState");
  EXPECT_EQ(c["schemaEncoding"], "omgidl");
  EXPECT_EQ(Json::parse(status(StatusLevel::kError, "no"))["level"], 2);
}

TEST(BridgeProtocol, MessageDataHeaderIsOpcodeSubscriptionAndTimeLittleEndian)
{
  const MessageHeader h = messageHeader(0x04030201U, 0x0c0b0a0908070605ULL);
  const MessageHeader expected{0x01, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0a, 0x0b, 0x0c};
  EXPECT_EQ(h, expected);
}

TEST(BridgeProtocol, ClientOpsAreRead)
{
  const auto s = std::get<Subscribe>(
      parseClientText(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":5}]})"));
  ASSERT_EQ(s.subscriptions.size(), 2U);
  EXPECT_EQ(s.subscriptions[1].id, 1U);
  EXPECT_EQ(s.subscriptions[1].channel_id, 5U);
  EXPECT_EQ(std::get<Unsubscribe>(parseClientText(R"({"op":"unsubscribe","subscriptionIds":[0,1]})")).subscription_ids,
            (std::vector<std::uint32_t>{0, 1}));
  const auto a = std::get<ClientAdvertise>(parseClientText(
      R"({"op":"advertise","channels":[{"id":2,"topic":"quad/planning/goal","encoding":"cdr","schemaName":"quad::msg::Goal"}]})"));
  ASSERT_EQ(a.channels.size(), 1U);
  EXPECT_EQ(a.channels[0].topic, "quad/planning/goal");
  EXPECT_EQ(std::get<ClientUnadvertise>(parseClientText(R"({"op":"unadvertise","channelIds":[2]})")).channel_ids,
            std::vector<std::uint32_t>{2});
  EXPECT_EQ(std::get<Unsupported>(parseClientText(R"({"op":"getParameters","parameterNames":[]})")).op, "getParameters");
}

TEST(BridgeProtocol, MalformedClientMessagesAreRefusedNamingOpAndField)
{
  const auto refused = [](const std::string& text) {
    try {
      parseClientText(text);
    } catch (const ProtocolError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused("not json"), "a text message that is not a JSON object");
  EXPECT_EQ(refused(R"({"subscriptions":[]})"), "message: no 'op'");
  EXPECT_EQ(refused(R"({"op":"subscribe"})"), "subscribe: no 'subscriptions'");
  EXPECT_EQ(refused(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":3}]})"),
            "subscribe: 'id' is -1, not a 32-bit unsigned number");
  EXPECT_EQ(refused(R"({"op":"unsubscribe","subscriptionIds":["a"]})"),
            "unsubscribe: 'subscriptionIds' holds \"a\", not a 32-bit unsigned number");
  EXPECT_EQ(refused(R"({"op":"advertise","channels":[{"id":1,"topic":5,"encoding":"cdr","schemaName":"x"}]})"),
            "advertise: 'topic' is 5, not a string");
}

TEST(BridgeProtocol, ClientMessageDataGivesItsChannelAndPayload)
{
  const std::vector<std::uint8_t> bytes{0x01, 0x02, 0x01, 0x00, 0x00, 0xaa, 0xbb};
  const ClientMessage m = parseClientBinary(bytes);
  EXPECT_EQ(m.channel_id, 0x102U);
  ASSERT_EQ(m.payload.size(), 2U);
  EXPECT_EQ(m.payload[1], 0xbb);
  EXPECT_THROW(parseClientBinary(std::vector<std::uint8_t>{0x02, 0, 0, 0, 0}), ProtocolError);
  EXPECT_THROW(parseClientBinary(std::vector<std::uint8_t>{0x01, 0}), ProtocolError);
  EXPECT_THROW(parseClientBinary({}), ProtocolError);
}

}  // namespace
}  // namespace quad::bridge
