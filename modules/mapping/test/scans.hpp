// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Scans of a known world for the mapping tests: one box in an open field, seen by the
/// plant's depth camera without noise.

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
