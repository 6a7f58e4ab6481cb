// SPDX-License-Identifier: BSD-3-Clause
// The consumer's voxel table against an ordered map of the same operations, fixed seeds.
#include "quad/mapping/voxel_map.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

namespace quad::mapping {
namespace {

using Reference = std::map<std::tuple<int, int, int>, VoxelState>;

void expectSame(const Reference& reference, const VoxelMap& map)
{
  ASSERT_EQ(map.known(), reference.size());
  const auto contents = map.contents();
  ASSERT_EQ(contents.size(), reference.size());
  auto it = reference.begin();
  for (const auto& c : contents) {
    EXPECT_EQ(std::make_tuple(c.index.x(), c.index.y(), c.index.z()), it->first);
    EXPECT_EQ(c.state, it->second);
    EXPECT_EQ(map.classify(c.index), it->second);
    ++it;
  }
}

// Dense clusters of sets and erases (runs of neighbouring keys are where linear probing's
// deletion can lose a voxel), with negative and large coordinates, growing past several
// table sizes and shrinking back.
TEST(VoxelMap, HoldsExactlyWhatTheChangesLeftAfterEverySetAndErase)
{
  std::mt19937_64 rng(11);
  VoxelMap map(0.2);
  Reference reference;
  for (int round = 0; round < 40; ++round) {
    std::uniform_int_distribution<int> centre(-40000, 40000);
    const VoxelIndex c(centre(rng), centre(rng) / 100, centre(rng) / 1000);
    std::uniform_int_distribution<int> near(-6, 6);
    std::uniform_int_distribution<int> state(0, 2);
    std::vector<VoxelChange> changes;
    const int n = round < 25 ? 3000 : 1500;
    for (int k = 0; k < n; ++k) {
      const VoxelIndex i = c + VoxelIndex(near(rng), near(rng), near(rng));
      // Later rounds erase more than they set: the table empties again.
      const auto s = static_cast<VoxelState>(round < 25 ? state(rng) : (state(rng) == 2 ? 1 : 0));
      changes.push_back({i, s});
      if (s == VoxelState::kUnknown) {
        reference.erase({i.x(), i.y(), i.z()});
      } else {
        reference[{i.x(), i.y(), i.z()}] = s;
      }
    }
    map.apply(changes);
    expectSame(reference, map);
    EXPECT_EQ(map.classify(c + VoxelIndex(7, 0, 0)), VoxelState::kUnknown);
  }
}

TEST(VoxelMap, SortsByIndexLikeIndexLess)
{
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> coord(-300000, 300000);
  for (const std::size_t n : {10U, 100000U}) {
    std::vector<VoxelChange> voxels;
    for (std::size_t k = 0; k < n; ++k) {
      voxels.push_back({VoxelIndex(coord(rng) / 1000, coord(rng), coord(rng) / 10), VoxelState::kFree});
    }
    auto expected = voxels;
    std::stable_sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return indexLess(a.index, b.index); });
    sortByIndex(voxels);
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_EQ(voxels[k].index, expected[k].index) << k;
    }
  }
}

TEST(VoxelMap, VoxelsBeyondAnyMapsReachAreNotHeld)
{
  VoxelMap map(0.2);
  map.apply({{VoxelIndex(1 << 20, 0, 0), VoxelState::kOccupied}, {VoxelIndex(0, 0, 1), VoxelState::kFree}});
  EXPECT_EQ(map.known(), 1U);
  EXPECT_EQ(map.classify(VoxelIndex(1 << 20, 0, 0)), VoxelState::kUnknown);
  // Sorting still orders them, by the plain comparison.
  std::vector<VoxelChange> voxels{{VoxelIndex(1 << 20, 0, 0), VoxelState::kFree}, {VoxelIndex(-5, 0, 0), VoxelState::kFree}};
  sortByIndex(voxels);
  EXPECT_EQ(voxels.front().index, VoxelIndex(-5, 0, 0));
}

}  // namespace
}  // namespace quad::mapping
