// SPDX-License-Identifier: BSD-3-Clause
// The scan's key set gives the same keys, flags and order with its window as hashed alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <tuple>
#include <vector>

#include "quad/mapping/map_tree.hpp"

namespace quad::mapping {
namespace {

using Entry = std::tuple<unsigned, unsigned, unsigned, bool>;

std::vector<Entry> contents(const ScanKeySet& set)
{
  std::vector<Entry> out;
  set.forEach([&](const octomap::OcTreeKey& k, bool occupied) { out.emplace_back(k[0], k[1], k[2], occupied); });
  return out;
}

TEST(ScanKeySet, GivesTheSameKeysFlagsAndOrderWithItsWindowAsHashedAlone)
{
  std::mt19937_64 rng(5);
  const octomap::OcTreeKey centre(32768, 32768, 32768);
  // Keys up to 12 voxels from the centre, around a window of radius 8: inside, on its faces
  // and outside; many repeated, freed and hit in either order.
  std::uniform_int_distribution<int> offset(-12, 12);
  ScanKeySet windowed;
  ScanKeySet hashed;
  for (int scan = 0; scan < 20; ++scan) {
    windowed.clear(centre, 8);
    hashed.clear();
    for (int i = 0; i < 3000; ++i) {
      const octomap::OcTreeKey k(static_cast<octomap::key_type>(centre[0] + offset(rng)),
                                 static_cast<octomap::key_type>(centre[1] + offset(rng)),
                                 static_cast<octomap::key_type>(centre[2] + offset(rng)));
      if (rng() % 4 == 0) {
        windowed.insertOccupied(k);
        hashed.insertOccupied(k);
      } else {
        windowed.insertFree(k);
        hashed.insertFree(k);
      }
    }
    const std::vector<Entry> a = contents(windowed);
    ASSERT_EQ(a, contents(hashed)) << "scan " << scan;
    ASSERT_EQ(windowed.size(), a.size());
    // Both kinds of key, and both flags, were there.
    const auto inside = [&](const Entry& e) {
      return std::abs(static_cast<int>(std::get<0>(e)) - 32768) <= 8 &&
             std::abs(static_cast<int>(std::get<1>(e)) - 32768) <= 8 &&
             std::abs(static_cast<int>(std::get<2>(e)) - 32768) <= 8;
    };
    EXPECT_GT(std::count_if(a.begin(), a.end(), inside), 100);
    EXPECT_GT(std::count_if(a.begin(), a.end(), [&](const Entry& e) { return !inside(e); }), 100);
    EXPECT_GT(std::count_if(a.begin(), a.end(), [](const Entry& e) { return std::get<3>(e); }), 100);
  }
}

TEST(ScanKeySet, AWindowTooWideForItsLimitHashesEveryKey)
{
  ScanKeySet set;
  set.clear(octomap::OcTreeKey(100, 100, 100), ScanKeySet::kMaxWindowRadius + 1);
  set.insertFree(octomap::OcTreeKey(100, 100, 100));
  set.insertOccupied(octomap::OcTreeKey(100, 100, 100));
  set.insertFree(octomap::OcTreeKey(101, 100, 100));
  EXPECT_EQ(contents(set), (std::vector<Entry>{{100, 100, 100, true}, {101, 100, 100, false}}));
}

}  // namespace
}  // namespace quad::mapping
