// SPDX-License-Identifier: BSD-3-Clause
// Plant faults through quad/system/fault commands and back.
#include "quad/plant_messages/faults.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace quad::plant {
namespace {

// GIVEN a fault of each kind the plant applies WHEN it is written as a command and read back
// THEN it is the same fault (its start is the reader's time).
TEST(PlantFaultCommands, EveryKindSurvivesTheRoundTrip)
{
  std::vector<Fault> faults(6);
  faults[0].kind = Fault::Kind::kMotor;
  faults[0].rotor = 2;
  faults[0].magnitude = 0.4;
  faults[1].kind = Fault::Kind::kSensorDropout;
  faults[1].sensor = Sensor::kPosition;
  faults[2].kind = Fault::Kind::kSensorNoise;
  faults[2].sensor = Sensor::kBaro;
  faults[2].magnitude = 0.3;
  faults[3].kind = Fault::Kind::kSensorOffset;
  faults[3].sensor = Sensor::kMag;
  faults[3].offset = {10.0, -2.0, 0.5};
  faults[4].kind = Fault::Kind::kPush;
  faults[4].force_W = {0.0, 24.0, 0.0};
  faults[5].kind = Fault::Kind::kCellLoss;
  faults[5].cells = 2;
  for (std::size_t i = 0; i < faults.size(); ++i) {
    Fault& f = faults[i];
    f.id = static_cast<std::uint32_t>(i + 1);
    f.duration_ns = 1'500'000'000;
    std::string why;
    const auto back = faultFrom(toCommand(f), 7'000'000'000, why);
    ASSERT_TRUE(back) << f.describe() << ": " << why;
    EXPECT_EQ(back->describe(), f.describe());
    EXPECT_EQ(back->start_ns, 7'000'000'000);
    EXPECT_EQ(back->duration_ns, f.duration_ns);
  }
}

TEST(PlantFaultCommands, AnOffsetThatIsNotFiniteOrOnNoSensorIsRefusedSayingWhy)
{
  Fault f;
  f.id = 9;
  f.kind = Fault::Kind::kSensorOffset;
  f.sensor = Sensor::kPosition;
  f.offset = {std::nan(""), 0.0, 0.0};
  std::string why;
  EXPECT_FALSE(faultFrom(toCommand(f), 0, why));
  EXPECT_EQ(why, "sensor offset is not finite");
  f.offset = {1.0, 0.0, 0.0};
  auto c = toCommand(f);
  c.target("lidar");
  EXPECT_FALSE(faultFrom(c, 0, why));
  EXPECT_EQ(why, "target 'lidar' is not a plant sensor (depth, imu, state, position, baro, mag, range or range_up)");
}

}  // namespace
}  // namespace quad::plant
