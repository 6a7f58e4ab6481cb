// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quad::display {
namespace {

/// Whether p lies inside the shape (boxes and spheres as drawn: centre, axes, size).
bool insideShape(const Shape& s, const Vector3& p)
{
  const Vector3 local = geometry::rotate(s.q_WS.conjugate(), p - s.centre_W);
  const Vector3 half = s.size / 2.0;
  switch (s.kind) {
    case Shape::Kind::kBox:
      return std::abs(local.x()) <= half.x() && std::abs(local.y()) <= half.y() && std::abs(local.z()) <= half.z();
    case Shape::Kind::kCylinder:
      return local.head<2>().norm() <= half.x() && std::abs(local.z()) <= half.z();
    case Shape::Kind::kSphere:
      return local.norm() <= half.x();
  }
  return false;
}

TEST(Scene, EachShapeCoversExactlyItsObstacle)
{
  std::vector<world::Obstacle> obstacles{
      world::Obstacle::makeBox({{10, 1, 2}, {2, 3, 4}, 0.3}),
      world::Obstacle::makeCylinder({20, -2, 0.4, 8}),
      world::Obstacle::makeSphere({{30, 0, 3}, 1.2}),
  };
  const world::World w({{-5, -10, 0}, {60, 10, 10}}, {0, 0, 0}, {50, 0, 2}, obstacles);
  const auto shapes = obstacleShapes(w);
  ASSERT_EQ(shapes.size(), obstacles.size());
  // Points sampled around each obstacle are inside its shape exactly when inside the obstacle
  // (away from the surface, where rounding decides).
  std::mt19937 rng(5);
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    Vector3 lo, hi;
    obstacles[k].bounds(lo, hi);
    std::uniform_real_distribution<double> ux(lo.x() - 1, hi.x() + 1), uy(lo.y() - 1, hi.y() + 1),
        uz(std::max(lo.z() - 1, 0.0), hi.z() + 1);
    for (int i = 0; i < 2000; ++i) {
      const Vector3 p(ux(rng), uy(rng), uz(rng));
      const double d = obstacles[k].signedDistance(p);
      if (std::abs(d) > 1e-6) {
        EXPECT_EQ(insideShape(shapes[k], p), d < 0.0) << k << " at " << p.transpose();
      }
    }
  }
}

TEST(Scene, AMapsBoxesHoldEachOccupiedVoxelOnceAndNothingElse)
{
  // Property, on random voxel sets of several densities: the centre of every voxel in and
  // around the map lies in exactly one box when occupied, in none when free; the boxes are
  // axis-aligned and at most one per voxel.
  std::mt19937 rng(17);
  for (int trial = 0; trial < 40; ++trial) {
    const double res = 0.05 + 0.05 * (trial % 3);
    const geometry::VoxelGrid grid(res);
    const double density = 0.1 + 0.2 * (trial % 5);
    std::vector<geometry::VoxelIndex> occupied;
    std::bernoulli_distribution pick(density);
    for (int z = -2; z < 4; ++z) {
      for (int y = -3; y < 5; ++y) {
        for (int x = -4; x < 6; ++x) {
          if (pick(rng)) {
            occupied.emplace_back(x, y, z);
          }
        }
      }
    }
    if (occupied.empty()) {
      continue;
    }
    const world::VoxelMap map("random", grid, occupied);
    const auto boxes = mapShapes(map);
    ASSERT_LE(boxes.size(), map.occupiedVoxels().size());
    for (const auto& b : boxes) {
      ASSERT_EQ(b.kind, Shape::Kind::kBox);
      ASSERT_EQ(b.q_WS.w, 1.0);
    }
    for (int z = -3; z < 5; ++z) {
      for (int y = -4; y < 6; ++y) {
        for (int x = -5; x < 7; ++x) {
          const geometry::VoxelIndex i(x, y, z);
          const Vector3 c = grid.centre(i);
          int holding = 0;
          for (const auto& b : boxes) {
            holding += insideShape(b, c) ? 1 : 0;
          }
          ASSERT_EQ(holding, map.occupied(i) ? 1 : 0) << "voxel " << i.transpose() << ", trial " << trial;
        }
      }
    }
  }
}

TEST(Scene, AWallOfVoxelsIsOneBox)
{
  const geometry::VoxelGrid grid(0.1);
  std::vector<geometry::VoxelIndex> wall;
  for (int z = 0; z < 3; ++z) {
    for (int y = 0; y < 20; ++y) {
      for (int x = 5; x < 8; ++x) {
        wall.emplace_back(x, y, z);
      }
    }
  }
  const auto boxes = mapShapes(world::VoxelMap("wall", grid, wall));
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].size.x(), 0.3, 1e-12);
  EXPECT_NEAR(boxes[0].size.y(), 2.0, 1e-12);
  EXPECT_NEAR(boxes[0].size.z(), 0.3, 1e-12);
  EXPECT_NEAR(boxes[0].centre_W.x(), 0.65, 1e-12);
  EXPECT_NEAR(boxes[0].centre_W.y(), 1.0, 1e-12);
  EXPECT_NEAR(boxes[0].centre_W.z(), 0.15, 1e-12);
}

TEST(Scene, TheWorldsShapesAreItsObstaclesThenItsMaps)
{
  const geometry::VoxelGrid grid(0.1);
  std::vector<world::VoxelMap> maps;
  maps.emplace_back("block", grid, std::vector<geometry::VoxelIndex>{{0, 0, 0}, {1, 0, 0}});
  const world::World w({{-5, -5, 0}, {5, 5, 5}}, {-4, 0, 1}, {4, 0, 1},
                       {world::Obstacle::makeSphere({{2, 2, 2}, 0.5})}, 0.0, std::move(maps));
  const auto shapes = worldShapes(w);
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(shapes[0].kind, Shape::Kind::kSphere);
  EXPECT_EQ(shapes[1].kind, Shape::Kind::kBox);
  EXPECT_NEAR(shapes[1].size.x(), 0.2, 1e-12);
}

TEST(Scene, TheGoalIsASphereOfItsRadius)
{
  const Shape g = goalShape({1, 2, 3}, 0.25);
  EXPECT_EQ(g.kind, Shape::Kind::kSphere);
  EXPECT_EQ(g.centre_W, Vector3(1, 2, 3));
  EXPECT_EQ(g.size, Vector3::Constant(0.5));
}

}  // namespace
}  // namespace quad::display
