// SPDX-License-Identifier: BSD-3-Clause
// The flat voxel table against an ordered map of the same operations, fixed seeds.
#include "quad/geometry/voxel_table.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

namespace quad::geometry {
namespace {

using Reference = std::map<std::tuple<int, int, int>, std::uint8_t>;

void expectSame(const Reference& reference, const VoxelTable& table)
{
  ASSERT_EQ(table.size(), reference.size());
  Reference held;
  for (const std::uint64_t w : table.words()) {
    const VoxelIndex i = VoxelTable::indexOf(w);
    held[{i.x(), i.y(), i.z()}] = VoxelTable::stateOf(w);
    EXPECT_EQ(table.get(i), VoxelTable::stateOf(w));
  }
  EXPECT_EQ(held, reference);
}

// Clusters of sets and erases (linear probing's deletion can lose a voxel in a run of
// neighbouring keys), every state 1 to 3, growing, reserved ahead, emptied and filled again.
TEST(VoxelTable, HoldsExactlyWhatItWasLeftWithAfterEverySetEraseReserveAndClear)
{
  std::mt19937_64 rng(5);
  VoxelTable table;
  Reference reference;
  for (int round = 0; round < 30; ++round) {
    std::uniform_int_distribution<int> centre(-500000, 500000);
    const VoxelIndex c(centre(rng), centre(rng) / 10, centre(rng) / 1000);
    std::uniform_int_distribution<int> near(-5, 5);
    std::uniform_int_distribution<int> state(0, 3);
    if (round == 10) {
      table.reserve(50000);
    }
    if (round == 20) {
      table.clear();
      reference.clear();
    }
    for (int k = 0; k < 2000; ++k) {
      const VoxelIndex i = c + VoxelIndex(near(rng), near(rng), near(rng));
      const auto s = static_cast<std::uint8_t>(state(rng));
      table.set(i, s);
      if (s == 0) {
        reference.erase({i.x(), i.y(), i.z()});
      } else {
        reference[{i.x(), i.y(), i.z()}] = s;
      }
    }
    expectSame(reference, table);
    EXPECT_EQ(table.get(c + VoxelIndex(6, 0, 0)), 0);
  }
}

TEST(VoxelTable, VoxelsBeyondTwoToTheNineteenAreNotHeld)
{
  VoxelTable table;
  table.set(VoxelIndex(1 << 19, 0, 0), 2);
  table.set(VoxelIndex(0, -(1 << 19) - 1, 0), 2);
  table.set(VoxelIndex((1 << 19) - 1, -(1 << 19), 0), 1);
  EXPECT_EQ(table.size(), 1U);
  EXPECT_EQ(table.get(VoxelIndex(1 << 19, 0, 0)), 0);
  EXPECT_EQ(table.get(VoxelIndex((1 << 19) - 1, -(1 << 19), 0)), 1);
}

TEST(VoxelTable, WordsSortAsTheirIndicesDo)
{
  const VoxelIndex a(-3, 7, 1), b(-3, 8, -9), c(2, -100, 0);
  EXPECT_LT(VoxelTable::wordOf(a, 3), VoxelTable::wordOf(b, 1));
  EXPECT_LT(VoxelTable::wordOf(b, 3), VoxelTable::wordOf(c, 1));
  EXPECT_EQ(VoxelTable::indexOf(VoxelTable::wordOf(a, 2)), a);
  EXPECT_EQ(VoxelTable::stateOf(VoxelTable::wordOf(a, 2)), 2);
}

}  // namespace
}  // namespace quad::geometry
