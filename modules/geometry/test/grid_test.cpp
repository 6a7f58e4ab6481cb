// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/grid.hpp"

#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <random>

#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

TEST(Grid, VoxelCentresMapToThemselves)
{
  const VoxelGrid grid(0.2);
  for (int x = -30; x <= 30; x += 3) {
    for (int y = -30; y <= 30; y += 7) {
      for (int z = -5; z <= 5; ++z) {
        const VoxelIndex i(x, y, z);
        EXPECT_EQ(grid.toIndex(grid.centre(i)), i);
      }
    }
  }
}

TEST(Grid, EveryPointLiesInTheBoxOfItsVoxel)
{
  const VoxelGrid grid(0.15);
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (int k = 0; k < 10000; ++k) {
    const Vector3 p(u(rng), u(rng), u(rng));
    const Vector3 offset = p - grid.centre(grid.toIndex(p));
    EXPECT_LE(offset.cwiseAbs().maxCoeff(), 0.075 + 1e-12) << p.transpose();
  }
  EXPECT_EQ(grid.toIndex(Vector3(-0.01, 0.0, 0.15)), VoxelIndex(-1, 0, 1));  // lower faces belong
  EXPECT_THROW(VoxelGrid(0.0), std::invalid_argument);
  EXPECT_THROW(VoxelGrid(-1.0), std::invalid_argument);
}

TEST(Grid, IndicesAgreeWithOctomapKeysAtTheSameResolution)
{
  for (const double res : {0.05, 0.1, 0.2, 0.25}) {
    const VoxelGrid grid(res);
    octomap::OcTree tree(res);
    std::mt19937_64 rng(test::kSeed);
    std::uniform_real_distribution<double> u(-100.0, 100.0);
    for (int k = 0; k < 5000; ++k) {
      // Random points, and points exactly on voxel faces.
      Vector3 p(u(rng), u(rng), u(rng));
      if (k % 2 == 0) {
        p = (p / res).array().round().matrix() * res;
      }
      const octomap::OcTreeKey key = tree.coordToKey(octomap::point3d(
          static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
      // OctoMap takes float points: compare on the point it actually saw.
      const Vector3 seen(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
      const auto ours = grid.octomapKey(grid.toIndex(seen));
      ASSERT_TRUE(ours.has_value());
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ((*ours)[a], key[static_cast<unsigned>(a)]) << "res " << res << " p " << seen.transpose();
      }
      const octomap::point3d c = tree.keyToCoord(key);
      EXPECT_NEAR(grid.centre(grid.toIndex(seen)).x(), c.x(), 1e-4);
    }
  }
}

TEST(Grid, LatticeCellsAndVoxelsAreInBijection)
{
  const Lattice lattice(VoxelGrid(0.5), Vector3(-2.0, -1.0, 0.0), Vector3(3.0, 1.0, 2.0));
  // Centres within [min, max]: x −1.75 … 2.75 (10), y −0.75 … 0.75 (4), z 0.25 … 1.75 (4).
  EXPECT_EQ(lattice.dims(), Eigen::Vector3i(10, 4, 4));
  EXPECT_EQ(lattice.size(), 160);
  for (std::int64_t c = 0; c < lattice.size(); ++c) {
    const VoxelIndex v = lattice.voxel(c);
    EXPECT_EQ(lattice.cell(v), c);
    EXPECT_EQ(lattice.cellAt(lattice.centre(c)), c);
  }
  EXPECT_FALSE(lattice.cell(lattice.origin() - VoxelIndex(1, 0, 0)).has_value());
  EXPECT_FALSE(lattice.cellAt(Vector3(10, 0, 1)).has_value());
  // Outside, the nearest cell is the boundary cell next to the point; inside, the point's own.
  EXPECT_EQ(lattice.centre(lattice.nearestCell(Vector3(10, 0.3, -4))), Vector3(2.75, 0.25, 0.25));
  EXPECT_EQ(lattice.nearestCell(Vector3(0.1, -0.6, 1.1)), *lattice.cellAt(Vector3(0.1, -0.6, 1.1)));
  EXPECT_THROW(lattice.voxel(160), std::out_of_range);
  EXPECT_THROW(lattice.voxel(-1), std::out_of_range);
  EXPECT_THROW(Lattice(VoxelGrid(0.5), Vector3(0, 0, 0), Vector3(0.1, 1, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace quad::geometry
