// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Scans of a known world for the mapping tests: one box in an open field, seen by the
/// plant's depth camera without noise, or with noise added to each point.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "quad/mapping/mapper.hpp"
#include "quad/plant/sensors.hpp"

namespace quad::mapping::test {

/// A world with one box (x 5..7, y −1..1, z 0..3) in an open field.
inline world::World boxWorld()
{
  return world::World(world::Bounds{Vector3(-20, -20, 0), Vector3(40, 20, 20)}, Vector3::Zero(), Vector3(30, 0, 2),
                      {world::Obstacle::makeBox({Vector3(6, 0, 1.5), Vector3(2, 2, 3), 0.0})});
}

/// What the plant's camera sees from `p` facing yaw, as a world-frame scan.
inline Scan scanFrom(const world::World& world, const Vector3& p, double yaw, std::mt19937_64& rng)
{
  plant::DepthCameraConfig config;
  config.width = 64;
  config.height = 48;
  config.max_range = 15.0;
  config.noise_std = 0.0;
  config.position_B = Vector3::Zero();
  const plant::DepthCamera camera(config);
  const geometry::Pose3 body{p, geometry::fromAxisAngle(Vector3::UnitZ(), yaw)};
  const plant::DepthScan depth = camera.capture(world, body, rng);
  Scan scan;
  scan.origin_W = depth.sensor_W.p;
  scan.max_range = config.max_range;
  for (const auto& point : depth.points_S) {
    scan.points_W.push_back(depth.sensor_W.transform(point.cast<double>()));
  }
  return scan;
}

/// A mapper's config limited to a box around boxWorld()'s box, 8 m of range.
inline MapperConfig boxedConfig()
{
  MapperConfig config;
  config.max_range = 8.0;
  config.box = std::make_pair(Vector3(-1.0, -3.0, 0.0), Vector3(8.0, 3.0, 3.0));
  return config;
}

/// `count` scans of boxWorld() from a camera moving towards the box, jittered, each point
/// moved by 0.1 m noise: voxels go up and down, siblings are pruned and expanded again.
inline std::vector<Scan> noisyScans(int count, std::uint64_t seed)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Scan> scans;
  for (int k = 0; k < count; ++k) {
    Scan scan = scanFrom(world, Vector3(-0.5 + 0.1 * k, 0.8 * u(rng), 1.5 + 0.4 * u(rng)), 0.3 * u(rng), rng);
    for (Vector3& p : scan.points_W) {
      p += Vector3(noise(rng), noise(rng), noise(rng));
    }
    scans.push_back(std::move(scan));
  }
  return scans;
}

/// `actual` holds exactly `expected` (both sorted by index, as contents() and
/// classification() give them).
inline void expectSameClassification(const std::vector<VoxelChange>& expected, const std::vector<VoxelChange>& actual)
{
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(actual[i].index, expected[i].index) << i;
    ASSERT_EQ(actual[i].state, expected[i].state) << i;
  }
}

}  // namespace quad::mapping::test
