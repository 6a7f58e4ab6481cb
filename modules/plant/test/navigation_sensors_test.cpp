// SPDX-License-Identifier: BSD-3-Clause
// The navigation aids' statistics and geometry, fixed seeds.
#include "quad/plant/navigation_sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "quad/geometry/quaternion.hpp"

namespace quad::plant {
namespace {

TEST(PositionSensor, FixesScatterByTheirNoiseAroundTheTruth)
{
  std::mt19937_64 rng(2);
  PositionSensor sensor(PositionSensorConfig{});
  const Vector3 p(3.0, -1.0, 2.0);
  Vector3 sum = Vector3::Zero();
  double sum2 = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const auto fix = sensor.measure(p, rng);
    ASSERT_TRUE(fix);  // no outages configured
    EXPECT_EQ(fix->std_dev, 0.02);
    sum += fix->p_W;
    sum2 += (fix->p_W - p).squaredNorm() / 3.0;
  }
  EXPECT_LT((sum / n - p).norm(), 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.02, 0.0005);
}

// GIVEN outages at λ per second lasting τ on average WHEN fixes fall due for a long time
// THEN the share of missing fixes is the renewal process's λτ / (1 + λτ), in outages of
// mean length τ.
TEST(PositionSensor, OutagesTakeTheShareOfTimeTheirRateAndLengthGive)
{
  std::mt19937_64 rng(4);
  PositionSensorConfig config;
  config.outages_per_minute = 6.0;  // λ = 0.1 /s
  config.outage_duration = 2.0;
  PositionSensor sensor(config);
  const int n = 200000;  // 20,000 s at 10 Hz
  int missing = 0;
  int outages = 0;
  bool was_missing = false;
  for (int k = 0; k < n; ++k) {
    const bool missed = !sensor.measure(Vector3::Zero(), rng);
    missing += missed ? 1 : 0;
    outages += missed && !was_missing ? 1 : 0;
    was_missing = missed;
  }
  const double share = static_cast<double>(missing) / n;
  EXPECT_NEAR(share, 0.2 / 1.2, 0.02);
  // A run of missing samples is the outage's length rounded up to whole periods (+ 0.05 s).
  EXPECT_NEAR(missing * 0.1 / outages, 2.05, 0.15);
}

TEST(Barometer, ReadsTheHeightPlusAnOffsetThatStartsAtRandomAndDrifts)
{
  BarometerConfig config;
  std::mt19937_64 rng(6);
  // The offsets of many starts spread by offset_std.
  double offsets2 = 0.0;
  const int starts = 4000;
  for (int k = 0; k < starts; ++k) {
    offsets2 += std::pow(Barometer(config, rng).offset(), 2);
  }
  EXPECT_NEAR(std::sqrt(offsets2 / starts), config.offset_std, 0.02);
  // One barometer: readings average to height + offset, and the offset drifts as walk × √t.
  config.drift_walk = 0.0;
  Barometer still(config, rng);
  double sum = 0.0;
  for (int k = 0; k < 10000; ++k) {
    sum += still.measure(4.0, 0.04, rng);
  }
  EXPECT_NEAR(sum / 10000, 4.0 + still.offset(), 0.004);
  config.drift_walk = 0.01;
  double drift2 = 0.0;
  for (int k = 0; k < 500; ++k) {
    Barometer b(config, rng);
    const double start = b.offset();
    for (int s = 0; s < 1000; ++s) {  // 100 s
      b.measure(0.0, 0.1, rng);
    }
    drift2 += std::pow(b.offset() - start, 2);
  }
  EXPECT_NEAR(std::sqrt(drift2 / 500), 0.01 * 10.0, 0.01);
}

// GIVEN a level vehicle at yaw ψ WHEN the magnetometer reads the field THEN the reading's
// length is the field's (a rotation), and the heading from its horizontal part is ψ.
TEST(Magnetometer, ReadsEarthsFieldRotatedIntoTheBodyAndGivesTheHeading)
{
  MagnetometerConfig config;
  config.noise_std = 0.0;
  std::mt19937_64 rng(8);
  for (const double yaw : {-3.0, -1.2, 0.0, 0.4, 2.9}) {
    const auto q = geometry::fromAxisAngle(Vector3::UnitZ(), yaw);
    const Vector3 m_B = measureMagnetometer(config, q, Vector3::Zero(), rng);
    EXPECT_NEAR(m_B.norm(), config.field_W.norm(), 1e-9);
    // Earth's field points north (+y in ENU): in the body it is at angle π/2 − ψ from x.
    const double heading = std::atan2(m_B.y(), m_B.x());
    EXPECT_NEAR(std::remainder(heading - (M_PI / 2 - yaw), 2 * M_PI), 0.0, 1e-9) << yaw;
  }
  // A disturbance adds to Earth's field before the rotation.
  const Vector3 m_B = measureMagnetometer(config, {}, Vector3(5.0, 0.0, 0.0), rng);
  EXPECT_NEAR((m_B - (config.field_W + Vector3(5.0, 0.0, 0.0))).norm(), 0.0, 1e-9);
}

TEST(Rangefinder, ReadsHowFarBelowTheBodyTheSurfaceBeneathLiesAlongTheBodysDownAxis)
{
  RangefinderConfig config;
  config.noise_std = 0.0;
  const world::World w({{-20, -20, 0}, {20, 20, 30}}, {0, 0, 0}, {10, 0, 2},
                       {world::Obstacle::makeBox({{5, 0, 1.5}, {2, 2, 3}, 0.0})});  // top at 3 m
  std::mt19937_64 rng(3);
  const geometry::Quaternion level;
  // Over the ground plane, over the box's top, and standing on each.
  EXPECT_NEAR(*measureRange(config, w, {0, 0, 2}, level, kDownward, rng), 2.0, 1e-9);
  EXPECT_NEAR(*measureRange(config, w, {5, 0, 4.5}, level, kDownward, rng), 1.5, 1e-9);
  EXPECT_NEAR(*measureRange(config, w, {0, 0, 0}, level, kDownward, rng), 0.0, 1e-9);
  EXPECT_NEAR(*measureRange(config, w, {5, 0, 3}, level, kDownward, rng), 0.0, 1e-9);
  // Tilted by θ, the slant range to a level floor is h / cos θ.
  for (const double tilt : {0.1, 0.3, 0.6}) {
    const auto q = geometry::fromAxisAngle(Vector3::UnitX(), tilt);
    EXPECT_NEAR(*measureRange(config, w, {-5, -5, 2}, q, kDownward, rng), 2.0 / std::cos(tilt), 1e-9) << tilt;
  }
  // Beyond its reach: nothing.
  config.max_range = 1.0;
  EXPECT_FALSE(measureRange(config, w, {0, 0, 2}, level, kDownward, rng).has_value());
  EXPECT_NEAR(*measureRange(config, w, {0, 0, 0.5}, level, kDownward, rng), 0.5, 1e-9);
}

TEST(Rangefinder, LookingUpReadsHowFarAboveTheBodyTheCeilingOverItLies)
{
  RangefinderConfig config;
  config.noise_std = 0.0;
  // A slab from 2.5 to 2.7 m over x in [0, 4]; nothing over the rest (the bounds' top is no
  // surface).
  const world::World w({{-20, -20, 0}, {20, 20, 30}}, {0, 0, 0}, {10, 0, 2},
                       {world::Obstacle::makeBox({{2, 0, 2.6}, {4, 4, 0.2}, 0.0})});
  std::mt19937_64 rng(5);
  const geometry::Quaternion level;
  EXPECT_NEAR(*measureRange(config, w, {2, 0, 0}, level, kUpward, rng), 2.5, 1e-9);
  EXPECT_NEAR(*measureRange(config, w, {2, 0, 1.5}, level, kUpward, rng), 1.0, 1e-9);
  EXPECT_NEAR(*measureRange(config, w, {2, 0, 2.4}, level, kUpward, rng), 0.1, 1e-9);
  EXPECT_FALSE(measureRange(config, w, {-5, 0, 1}, level, kUpward, rng).has_value());
  // Standing on the slab, the ceiling is gone and the floor is the slab.
  EXPECT_FALSE(measureRange(config, w, {2, 0, 2.7}, level, kUpward, rng).has_value());
  EXPECT_NEAR(*measureRange(config, w, {2, 0, 2.7}, level, kDownward, rng), 0.0, 1e-9);
  // Tilted by θ, the slant range to a level ceiling is h / cos θ.
  for (const double tilt : {0.1, 0.3, 0.6}) {
    const auto q = geometry::fromAxisAngle(Vector3::UnitY(), tilt);
    EXPECT_NEAR(*measureRange(config, w, {2, 0, 1}, q, kUpward, rng), 1.5 / std::cos(tilt), 1e-9) << tilt;
  }
}

TEST(Rangefinder, ItsNoiseHasTheStatedSpreadAndNeverReadsBelowZero)
{
  RangefinderConfig config;
  config.noise_std = 0.05;
  const world::World w({{-20, -20, 0}, {20, 20, 30}}, {0, 0, 0}, {10, 0, 2}, {});
  std::mt19937_64 rng(4);
  double sum = 0.0;
  double sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double r = *measureRange(config, w, {0, 0, 3}, {}, kDownward, rng);
    sum += r - 3.0;
    sum2 += (r - 3.0) * (r - 3.0);
    ASSERT_GE(*measureRange(config, w, {0, 0, 0}, {}, kDownward, rng), 0.0);
  }
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.05, 0.002);
}

}  // namespace
}  // namespace quad::plant
