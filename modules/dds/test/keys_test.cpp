// SPDX-License-Identifier: BSD-3-Clause
// The DDS key of every message is header.vehicle_id alone.
#include "quad/dds/message_types.hpp"

#include <gtest/gtest.h>

namespace quad::dds {
namespace {

using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;

Handle keyOf(msg::VehicleState& s)
{
  MessageTraits<msg::VehicleState>::PubSubType type;
  Handle h;
  EXPECT_TRUE(type.getKey(&s, &h, false));
  return h;
}

TEST(Keys, SamplesOfOneVehicleAreOneInstanceWhateverTheirStampAndSequence)
{
  msg::VehicleState a;
  a.header().vehicle_id(3);
  a.header().stamp_ns(100);
  a.header().seq(1);
  msg::VehicleState b = a;
  b.header().stamp_ns(999'999);
  b.header().seq(2);
  b.p_W().x(5.0);
  EXPECT_EQ(keyOf(a), keyOf(b));
}

TEST(Keys, DifferentVehiclesAreDifferentInstances)
{
  msg::VehicleState a;
  a.header().vehicle_id(3);
  msg::VehicleState b;
  b.header().vehicle_id(4);
  EXPECT_NE(keyOf(a), keyOf(b));
}

TEST(Keys, KeyHashIsTheBigEndianVehicleIdPaddedTo16Bytes)
{
  msg::VehicleState a;
  a.header().vehicle_id(0x01020304);
  const Handle h = keyOf(a);
  const std::uint8_t expected[16] = {1, 2, 3, 4};
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(h.value[i], expected[i]) << "byte " << i;
  }
}

using Payload = eprosima::fastrtps::rtps::SerializedPayload_t;

Payload serialized(msg::LockstepReport& report)
{
  MessageTraits<msg::LockstepReport>::PubSubType type;
  Payload payload(type.m_typeSize);
  EXPECT_TRUE(type.serialize(&report, &payload));
  return payload;
}

/// Deserializes into an object that still holds vehicle 7's sample, as a reader's history
/// does when it computes the key of each arriving sample, and says the key left behind.
Handle keyLeftBy(Payload& payload, bool* accepted)
{
  MessageTraits<msg::LockstepReport>::PubSubType type;
  msg::LockstepReport kept;
  kept.header().vehicle_id(7);
  *accepted = type.deserialize(&payload, &kept);
  Handle h;
  EXPECT_TRUE(type.getKey(&kept, &h, false));
  return h;
}

Handle vehicleKey(std::uint32_t id)
{
  Handle h;
  vehicleKeyHash(id, h);
  return h;
}

TEST(Keys, ASampleWhoseVehicleIdIsNoVehicleIdIsRefusedAndInventsNoInstance)
{
  msg::LockstepReport report;
  report.participant("mapping");
  report.header().vehicle_id(common::kMaxVehicleId);
  Payload fine = serialized(report);
  bool accepted = false;
  EXPECT_EQ(keyLeftBy(fine, &accepted), vehicleKey(common::kMaxVehicleId));
  EXPECT_TRUE(accepted);

  // Bit 31 flipped on the way: 2,147,483,648.
  report.header().vehicle_id(0x80000000u);
  Payload flipped = serialized(report);
  const std::uint64_t refused_before = rejectedPayloadCount("quad::msg::LockstepReport");
  EXPECT_EQ(keyLeftBy(flipped, &accepted), vehicleKey(0));
  EXPECT_FALSE(accepted);
  EXPECT_EQ(rejectedPayloadCount("quad::msg::LockstepReport"), refused_before + 1);
  EXPECT_NE(rejectedPayloads().last.find("2147483648"), std::string::npos) << rejectedPayloads().last;
}

TEST(Keys, APayloadRefusedForItsIdlLeavesVehicleZeroNotTheLastKeyComputed)
{
  msg::LockstepReport report;
  report.participant("mapping");
  report.header().vehicle_id(3);
  Payload payload = serialized(report);
  // The participant string's length, after the encapsulation (4) and the header (32): past
  // its bound of 32.
  payload.data[4 + 32] = 200;
  bool accepted = true;
  EXPECT_EQ(keyLeftBy(payload, &accepted), vehicleKey(0));
  EXPECT_FALSE(accepted);
}

}  // namespace
}  // namespace quad::dds
