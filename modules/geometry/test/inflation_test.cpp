// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/inflation.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

/// Exact distance from a point to an axis-aligned box, computed from the box's corners.
double pointToBox(const Vector3& p, const Vector3& lo, const Vector3& hi)
{
  const Vector3 nearest = p.cwiseMax(lo).cwiseMin(hi);
  return (p - nearest).norm();
}

TEST(Inflation, ZeroRadiusBlocksOnlyTheVoxelItself)
{
  const auto offsets = inflationOffsets(0.0, 0.1);
  ASSERT_EQ(offsets.size(), 1U);
  EXPECT_EQ(offsets[0], VoxelIndex(0, 0, 0));
  EXPECT_THROW(inflationOffsets(-0.1, 0.1), std::invalid_argument);
}

TEST(Inflation, BlockedCellsAreExactlyThoseWithinTheRadiusOfAnOccupiedBox)
{
  // Property against brute force: random occupied voxels, every cell of a small lattice.
  const double res = 0.2;
  const VoxelGrid grid(res);
  const Lattice lattice(grid, Vector3(0, 0, 0), Vector3(4, 4, 2));
  std::mt19937_64 rng(test::kSeed);
  for (const double radius : {0.1, 0.25, 0.3, 0.45, 0.6}) {
    std::vector<VoxelIndex> occupied;
    std::uniform_int_distribution<std::int64_t> cell(0, lattice.size() - 1);
    for (int k = 0; k < 12; ++k) {
      occupied.push_back(lattice.voxel(cell(rng)));
    }
    std::set<std::int64_t> blocked;
    for (const auto& v : occupied) {
      for (const auto& d : inflationOffsets(radius, res)) {
        if (auto c = lattice.cell(v + d)) {
          blocked.insert(*c);
        }
      }
    }
    for (std::int64_t c = 0; c < lattice.size(); ++c) {
      const Vector3 centre = lattice.centre(c);
      bool near_box = false;
      for (const auto& v : occupied) {
        const Vector3 lo = v.cast<double>() * res;
        near_box = near_box || pointToBox(centre, lo, lo + Vector3::Constant(res)) <= radius + 1e-9 * res;
      }
      EXPECT_EQ(blocked.contains(c), near_box) << "radius " << radius << " cell " << c;
    }
  }
}

TEST(Inflation, OffsetsAreSymmetricSortedAndGrowWithTheRadius)
{
  const auto small = inflationOffsets(0.3, 0.1);
  const auto large = inflationOffsets(0.5, 0.1);
  const std::set<std::tuple<int, int, int>> small_set = [&] {
    std::set<std::tuple<int, int, int>> s;
    for (const auto& d : small) {
      s.insert({d.x(), d.y(), d.z()});
    }
    return s;
  }();
  for (const auto& d : small) {
    EXPECT_TRUE(small_set.contains({-d.x(), -d.y(), -d.z()}));
  }
  for (std::size_t i = 1; i < small.size(); ++i) {
    EXPECT_LE(centreToBoxDistance(small[i - 1], 0.1), centreToBoxDistance(small[i], 0.1));
  }
  EXPECT_GT(large.size(), small.size());
}

}  // namespace
}  // namespace quad::geometry
