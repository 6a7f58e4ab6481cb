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

}  // namespace
}  // namespace quad::dds
