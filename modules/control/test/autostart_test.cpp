// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/autostart.hpp"

#include <gtest/gtest.h>

namespace quad::control {
namespace {

TEST(Autostart, ArmsThenTakesOffAskingAgainUntilTheVehicleIsInTheAirAndNeverAfter)
{
  Autostart a(true);
  EXPECT_EQ(a.next(Mode::kDisarmed), Command::kArm);
  EXPECT_EQ(a.next(Mode::kDisarmed), Command::kArm);  // refused (no fresh state yet): again
  EXPECT_EQ(a.next(Mode::kIdle), Command::kTakeoff);
  EXPECT_EQ(a.next(Mode::kIdle), Command::kTakeoff);
  EXPECT_FALSE(a.done());
  EXPECT_EQ(a.next(Mode::kTakeoff), std::nullopt);
  EXPECT_TRUE(a.done());
  // Landed and disarmed after the flight: the landing is final.
  EXPECT_EQ(a.next(Mode::kIdle), std::nullopt);
  EXPECT_EQ(a.next(Mode::kDisarmed), std::nullopt);
}

TEST(Autostart, AVehicleTakenOverInFlightIsNeverArmedOrLaunchedByIt)
{
  for (const Mode m : {Mode::kMission, Mode::kHover, Mode::kLand, Mode::kFailsafeLand, Mode::kReturn}) {
    Autostart a(true);
    EXPECT_EQ(a.next(m), std::nullopt) << toString(m);
    EXPECT_EQ(a.next(Mode::kIdle), std::nullopt) << toString(m);
  }
}

TEST(Autostart, DisabledItNeverAsks)
{
  Autostart a(false);
  EXPECT_TRUE(a.done());
  EXPECT_EQ(a.next(Mode::kDisarmed), std::nullopt);
  EXPECT_EQ(a.next(Mode::kIdle), std::nullopt);
}

TEST(Autostart, EachReasonForARefusalIsNewOnceUntilAnotherComes)
{
  Autostart a(true);
  EXPECT_TRUE(a.newRefusal("arm refused: no fresh state"));
  EXPECT_FALSE(a.newRefusal("arm refused: no fresh state"));
  EXPECT_TRUE(a.newRefusal("takeoff refused: battery at its reserve"));
  EXPECT_TRUE(a.newRefusal("arm refused: no fresh state"));
}

}  // namespace
}  // namespace quad::control
