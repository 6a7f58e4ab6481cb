// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/land_detector.hpp"

#include <gtest/gtest.h>

namespace quad::control {
namespace {

VehicleState at(double z, double vz)
{
  VehicleState s;
  s.p_W = Vector3(1.0, 2.0, z);
  s.v_W = Vector3(0.0, 0.0, vz);
  s.q_WB = Quaternion::identity();
  return s;
}

TEST(LandDetector, TheFirstStateIsJudgedByTheRangefinderAndSpeedWhateverTheHeight)
{
  LandDetector on_platform;  // 2 m up, on what the rangefinder sees 1 cm below
  on_platform.onRange(0.01);
  EXPECT_TRUE(on_platform.update(0.0, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  EXPECT_TRUE(on_platform.judged());
  LandDetector hovering;  // as high, the floor 2 m below
  hovering.onRange(2.0);
  EXPECT_FALSE(hovering.update(0.0, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  LandDetector high;  // nothing within the rangefinder's reach
  high.onRange(std::nullopt);
  EXPECT_FALSE(high.update(0.0, Mode::kDisarmed, at(40.0, 0.0), 0.0));
  LandDetector falling;  // just above the ground, but falling
  falling.onRange(0.1);
  EXPECT_FALSE(falling.update(0.0, Mode::kDisarmed, at(0.1, -1.0), 0.0));
}

TEST(LandDetector, WithoutARangefinderReadingTheFirstStateWaitsThenIsJudgedByHeight)
{
  LandDetectorConfig c;
  c.range_wait = 0.25;
  LandDetector flying(c);
  // Not judged before the wait is over: taken for landed (nothing takes over), not judged
  // (nothing may arm it).
  EXPECT_TRUE(flying.update(1.0, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  EXPECT_FALSE(flying.judged());
  EXPECT_TRUE(flying.update(1.2, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  EXPECT_FALSE(flying.judged());
  EXPECT_FALSE(flying.update(1.25, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  EXPECT_TRUE(flying.judged());
  // A reading within the wait judges at once.
  LandDetector late_reading(c);
  EXPECT_TRUE(late_reading.update(1.0, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  late_reading.onRange(2.0);
  EXPECT_FALSE(late_reading.update(1.1, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  EXPECT_TRUE(late_reading.judged());
  // No wait: by height at once, as without a rangefinder.
  c.range_wait = 0.0;
  LandDetector ground(c);
  EXPECT_TRUE(ground.update(0.0, Mode::kDisarmed, at(0.05, 0.0), 0.0));
  LandDetector high(c);
  EXPECT_FALSE(high.update(0.0, Mode::kDisarmed, at(2.0, 0.0), 0.0));
  EXPECT_TRUE(high.judged());
}

TEST(LandDetector, TakingOffLeavesTheGroundAndALandingEndsOnlyAfterTheHold)
{
  LandDetectorConfig c;
  LandDetector d(c);
  ASSERT_TRUE(d.update(0.0, Mode::kIdle, at(0.0, 0.0), 0.0));
  EXPECT_FALSE(d.update(0.1, Mode::kTakeoff, at(0.0, 0.0), 1.1));
  // Sinking at the landing speed, or still but holding its weight: not landed.
  double t = 1.0;
  for (; t < 5.0; t += 0.004) {
    ASSERT_FALSE(d.update(t, Mode::kLand, at(1.0, -0.5), 0.95));
  }
  for (; t < 10.0; t += 0.004) {
    ASSERT_FALSE(d.update(t, Mode::kLand, at(0.0, 0.0), 0.95));
  }
  // Still on less thrust than the limit: landed once it held for hold_time, not before.
  const double still = t;
  while (!d.update(t, Mode::kLand, at(0.0, 0.01), 0.5)) {
    t += 0.004;
    ASSERT_LT(t, still + 2.0);
  }
  EXPECT_GE(t - still, c.hold_time - 1e-9);
  EXPECT_LT(t - still, c.hold_time + 0.01);
  // It stays landed on the ground (IDLE), and takes off again.
  EXPECT_TRUE(d.update(t + 1.0, Mode::kIdle, at(0.0, 0.0), 0.0));
  EXPECT_FALSE(d.update(t + 2.0, Mode::kTakeoff, at(0.0, 0.0), 1.2));
}

TEST(LandDetector, AMomentOfStillnessInTheDescentIsNotALanding)
{
  LandDetector d;
  d.update(0.0, Mode::kHover, at(2.0, 0.0), 1.0);
  double t = 0.0;
  for (int cycle = 0; cycle < 10; ++cycle) {
    for (int i = 0; i < 50; ++i, t += 0.004) {  // 0.2 s still on low thrust (starting the descent)
      ASSERT_FALSE(d.update(t, Mode::kLand, at(2.0, -0.05), 0.8));
    }
    ASSERT_FALSE(d.update(t, Mode::kLand, at(1.8, -0.5), 0.8));  // then sinking
    t += 0.004;
  }
}

// Without any state (the estimator lost), a blind descent on 0.85 of the weight reads less
// than gravity and is not a landing; at rest the accelerometer reads gravity and the
// gyroscope nothing, and after the hold it is.
TEST(LandDetector, WithoutAStateTheImuJudgesABlindDescent)
{
  LandDetector d;
  ASSERT_FALSE(d.update(0.0, Mode::kMission, at(3.0, 0.0), 1.0));
  const auto imu = [](double f, double w) { return InertialSample{Vector3(0.0, 0.0, f), Vector3(w, 0.0, 0.0)}; };
  double t = 0.0;
  for (; t < 2.0; t += 0.004) {
    ASSERT_FALSE(d.update(t, Mode::kFailsafeLand, imu(0.85 * 9.81, 0.0), 0.85)) << t;
  }
  // Touched down, but still rocking: not yet.
  for (; t < 3.0; t += 0.004) {
    ASSERT_FALSE(d.update(t, Mode::kFailsafeLand, imu(9.81, 0.5), 0.85)) << t;
  }
  const double rest = t;
  for (; t < rest + 0.49; t += 0.004) {
    ASSERT_FALSE(d.update(t, Mode::kFailsafeLand, imu(9.81 + 0.1, 0.01), 0.85)) << t;
  }
  EXPECT_TRUE(d.update(rest + 0.51, Mode::kFailsafeLand, imu(9.81, 0.01), 0.85));
}

}  // namespace
}  // namespace quad::control
