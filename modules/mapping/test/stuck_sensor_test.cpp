// SPDX-License-Identifier: BSD-3-Clause
// A stuck depth camera is told by a frame whose hits repeat the frame before's bit for bit;
// a live camera's noisy frames, and views of nothing but misses, are not.
#include "quad/mapping/stuck_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace quad::mapping {
namespace {

constexpr float kRange = 10.0F;

/// A 64 x 48 frame of hits at 3-6 m with 1 cm of range noise, seeded.
std::vector<std::array<float, 3>> noisyFrame(unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0F, 0.01F);
  std::vector<std::array<float, 3>> points;
  for (int v = 0; v < 48; ++v) {
    for (int u = 0; u < 64; ++u) {
      const float range = 3.0F + 3.0F * static_cast<float>(u) / 64.0F + noise(rng);
      points.push_back({range, 0.02F * static_cast<float>(u - 32) * range, 0.02F * static_cast<float>(v - 24) * range});
    }
  }
  return points;
}

TEST(StuckSensor, AFrameWhoseHitsRepeatTheFrameBeforeIsAStuckCamerasAndOnlyThat)
{
  StuckSensorCheck check;
  const auto frame = noisyFrame(1);
  EXPECT_FALSE(check.repeats(frame, kRange));  // the first: nothing before it
  EXPECT_TRUE(check.repeats(frame, kRange));   // sent again
  EXPECT_TRUE(check.repeats(frame, kRange));   // and again
  // A live camera: every frame's noise differs.
  for (unsigned seed = 2; seed < 50; ++seed) {
    EXPECT_FALSE(check.repeats(noisyFrame(seed), kRange)) << seed;
  }
  // One point's last bit changed is another frame.
  auto nudged = noisyFrame(49);
  nudged[100][0] = std::nextafter(nudged[100][0], 100.0F);
  EXPECT_FALSE(check.repeats(nudged, kRange));
  // A frame equal to one two frames back is not a repeat of the one before.
  EXPECT_FALSE(check.repeats(noisyFrame(2), kRange));
  EXPECT_FALSE(check.repeats(noisyFrame(3), kRange));
  EXPECT_FALSE(check.repeats(noisyFrame(2), kRange));
}

TEST(StuckSensor, AViewOfNothingButMissesRepeatsWithoutBeingAStuckCamera)
{
  // The open sky: every ray a miss, at the camera's range and beyond, the same every frame.
  std::vector<std::array<float, 3>> sky(64 * 48, {kRange * 1.5F, 0.0F, 0.0F});
  StuckSensorCheck check;
  for (int i = 0; i < 5; ++i) {
    EXPECT_FALSE(check.repeats(sky, kRange)) << i;
  }
  // One hit in it makes the same frame again a repeat.
  sky[7] = {kRange * 0.5F, 0.0F, 0.0F};
  EXPECT_FALSE(check.repeats(sky, kRange));
  EXPECT_TRUE(check.repeats(sky, kRange));
}

}  // namespace
}  // namespace quad::mapping
