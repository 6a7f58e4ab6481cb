// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/occupied_voxels.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

namespace quad::display {
namespace {

using mapping::VoxelState;

TEST(OccupiedVoxels, HoldsExactlyTheVoxelsWhoseLastChangeSaysOccupied)
{
  // Random change sets over a small block (so voxels change often), negative indices too,
  // against a replay into a plain map.
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> axis(-6, 6);
  std::uniform_int_distribution<int> state(0, 2);
  OccupiedVoxels held(0.2);
  std::map<std::tuple<int, int, int>, VoxelState> reference;
  for (int set = 0; set < 200; ++set) {
    std::vector<mapping::VoxelChange> changes;
    for (int k = 0; k < 30; ++k) {
      const geometry::VoxelIndex i(axis(rng), axis(rng), axis(rng) * 1000);
      const auto s = static_cast<VoxelState>(state(rng));
      changes.push_back({i, s});
      reference[{i.x(), i.y(), i.z()}] = s;
    }
    held.apply(changes);
  }
  std::vector<geometry::Vector3> expected;
  const geometry::VoxelGrid grid(0.2);
  for (const auto& [i, s] : reference) {
    if (s == VoxelState::kOccupied) {
      expected.push_back(grid.centre({std::get<0>(i), std::get<1>(i), std::get<2>(i)}));
    }
  }
  auto got = held.centres();
  const auto less = [](const geometry::Vector3& a, const geometry::Vector3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(got.begin(), got.end(), less);
  std::sort(expected.begin(), expected.end(), less);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_LE((got[k] - expected[k]).norm(), 1e-9) << k;
  }
}

TEST(OccupiedVoxels, ReportsAChangeOnlyWhenTheSetChanged)
{
  OccupiedVoxels held(0.5);
  EXPECT_FALSE(held.changed());
  held.apply({{{1, 2, 3}, VoxelState::kFree}});
  EXPECT_FALSE(held.changed());  // free was never held
  held.apply({{{1, 2, 3}, VoxelState::kOccupied}});
  EXPECT_TRUE(held.changed());
  EXPECT_EQ(held.centres().size(), 1U);
  EXPECT_FALSE(held.changed());
  held.apply({{{1, 2, 3}, VoxelState::kOccupied}});
  EXPECT_FALSE(held.changed());  // occupied again: nothing new
  held.apply({{{1, 2, 3}, VoxelState::kUnknown}});
  EXPECT_TRUE(held.changed());
  EXPECT_EQ(held.size(), 0U);
}

}  // namespace
}  // namespace quad::display
