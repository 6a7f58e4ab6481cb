// SPDX-License-Identifier: BSD-3-Clause
// The consumer's side of change sets and snapshots: whatever it missed and in whatever order
// snapshots arrive, once a gap is filled it holds exactly the mapper's classification.
#include "quad/mapping/map_follower.hpp"

#include <gtest/gtest.h>

#include <random>

#include "scans.hpp"

namespace quad::mapping {
namespace {

/// A mapper flying past the box, with each scan's change set and the snapshot after it.
struct Flight {
  Mapper mapper{MapperConfig{}};
  std::vector<std::vector<VoxelChange>> changes;        // [k]: update k + 1
  std::vector<std::vector<std::uint8_t>> snapshots;     // [k]: after update k + 1
  std::vector<std::vector<VoxelChange>> classification; // [k]: after update k + 1

  explicit Flight(int scans)
  {
    const world::World world = test::boxWorld();
    std::mt19937_64 rng(5);
    for (int k = 0; k < scans; ++k) {
      const auto r = mapper.integrate(test::scanFrom(world, Vector3(-1.0 + 0.4 * k, 0.2 * k - 2.0, 1.5), 0.1 * k, rng));
      changes.push_back(r.changes);
      snapshots.push_back(mapper.snapshot());
      classification.push_back(mapper.classification());
    }
  }
};

void expectSame(const std::vector<VoxelChange>& expected, const VoxelMap& held)
{
  test::expectSameClassification(expected, held.contents());
}

/// Updates 1..last of the flight, in order.
void applyInOrder(const Flight& f, std::uint64_t last, MapFollower& follower)
{
  for (std::uint64_t seq = 1; seq <= last; ++seq) {
    follower.update(seq, f.changes[seq - 1]);
  }
}

TEST(MapFollower, InOrderUpdatesNeedNoSnapshot)
{
  const Flight f(12);
  MapFollower follower(f.mapper.resolution());
  for (std::size_t k = 0; k < f.changes.size(); ++k) {
    follower.update(k + 1, f.changes[k]);
    EXPECT_FALSE(follower.gapOpen());
  }
  EXPECT_FALSE(follower.snapshot(12, f.snapshots[11]).has_value());  // nothing to fill
  expectSame(f.classification.back(), follower.held());
}

TEST(MapFollower, ALateJoinerWhoseSnapshotComesAfterLaterUpdatesCatchesUpExactly)
{
  const Flight f(20);
  MapFollower follower(f.mapper.resolution());
  // Joins at update 9; snapshot 8 is late: it arrives after updates 9..12.
  for (std::uint64_t seq = 9; seq <= 12; ++seq) {
    follower.update(seq, f.changes[seq - 1]);
  }
  EXPECT_TRUE(follower.gapOpen());
  EXPECT_FALSE(follower.snapshot(7, f.snapshots[6]).has_value());  // older than the hole
  EXPECT_TRUE(follower.gapOpen());
  const auto diff = follower.snapshot(8, f.snapshots[7]);
  ASSERT_TRUE(diff.has_value());
  EXPECT_EQ(follower.replayed(), 4U);
  EXPECT_FALSE(follower.gapOpen());
  expectSame(f.classification[11], follower.held());
  for (std::uint64_t seq = 13; seq <= 20; ++seq) {
    follower.update(seq, f.changes[seq - 1]);
  }
  expectSame(f.classification.back(), follower.held());
}

TEST(MapFollower, AMissedUpdateIsFilledByANewerSnapshotAndTheDiffReachesAnOutsideCopy)
{
  const Flight f(16);
  MapFollower follower(f.mapper.resolution());
  VoxelMap downstream(f.mapper.resolution());  // the planner's grid, fed only what the follower returns
  for (std::uint64_t seq = 1; seq <= 16; ++seq) {
    if (seq == 6) {
      continue;  // lost
    }
    downstream.apply(follower.update(seq, f.changes[seq - 1]));
    if (seq == 7) {
      EXPECT_TRUE(follower.gapOpen());
      EXPECT_EQ(follower.gaps(), 1U);
    }
    if (seq == 10) {
      const auto diff = follower.snapshot(9, f.snapshots[8]);  // covers update 6
      ASSERT_TRUE(diff.has_value());
      downstream.apply(*diff);
      EXPECT_FALSE(follower.gapOpen());
    }
  }
  expectSame(f.classification.back(), follower.held());
  expectSame(f.classification.back(), downstream);
}

TEST(MapFollower, AMapperStartedAgainWithoutItsMapIsFollowedFromScratch)
{
  // GIVEN a follower (and the planner's grid it feeds) at update 8 of one mapper
  const Flight before(8);
  MapFollower follower(before.mapper.resolution());
  VoxelMap downstream(before.mapper.resolution());
  for (std::uint64_t seq = 1; seq <= 8; ++seq) {
    downstream.apply(follower.update(seq, before.changes[seq - 1]));
  }
  // WHEN that mapper dies and one started again with an empty map numbers from 1
  const Flight after(3);
  for (std::uint64_t seq = 1; seq <= 3; ++seq) {
    downstream.apply(follower.update(seq, after.changes[seq - 1]));
  }
  // THEN both hold the new mapper's map, nothing of the old one's
  EXPECT_EQ(follower.restarts(), 1U);
  EXPECT_FALSE(follower.gapOpen());
  EXPECT_EQ(follower.appliedSeq(), 3U);
  expectSame(after.classification.back(), follower.held());
  expectSame(after.classification.back(), downstream);  // the old voxels are unknown again
  EXPECT_LT(after.classification.back().size(), before.classification.back().size());
}

TEST(MapFollower, ASnapshotAheadOfTheUpdatesFillsTheGapThatOpensLater)
{
  // GIVEN a follower at update 6 (a restarted planner, say, whose update reader matched
  // after update 7 was sent: 7 will never come)
  const Flight f(12);
  MapFollower follower(f.mapper.resolution());
  applyInOrder(f, 6, follower);
  // WHEN snapshot 8 arrives before update 8 shows the hole: kept, nothing changes yet
  EXPECT_FALSE(follower.snapshot(8, f.snapshots[7]).has_value());
  EXPECT_EQ(follower.appliedSeq(), 6U);
  // THEN update 8 opens the gap and the kept snapshot fills it at once: what the consumer
  // is given brings an outside copy to the mapper's map, and 9 on apply in order
  VoxelMap outside(f.mapper.resolution());
  for (std::uint64_t seq = 1; seq <= 6; ++seq) {
    outside.apply(f.changes[seq - 1]);
  }
  outside.apply(follower.update(8, f.changes[7]));
  EXPECT_FALSE(follower.gapOpen());
  EXPECT_EQ(follower.gaps(), 1U);
  expectSame(f.classification[7], follower.held());
  expectSame(f.classification[7], outside);
  for (std::uint64_t seq = 9; seq <= 12; ++seq) {
    outside.apply(follower.update(seq, f.changes[seq - 1]));
  }
  EXPECT_FALSE(follower.gapOpen());
  expectSame(f.classification.back(), follower.held());
  expectSame(f.classification.back(), outside);
}

TEST(MapFollower, AKeptSnapshotIsDroppedWhenTheUpdatesReachIt)
{
  const Flight f(12);
  MapFollower follower(f.mapper.resolution());
  applyInOrder(f, 6, follower);
  // Snapshot 8 ahead of updates 7 and 8, which then come in order: no gap, nothing filled;
  // a gap opening later is not filled by the stale snapshot.
  EXPECT_FALSE(follower.snapshot(8, f.snapshots[7]).has_value());
  follower.update(7, f.changes[6]);
  follower.update(8, f.changes[7]);
  EXPECT_EQ(follower.gaps(), 0U);
  follower.update(10, f.changes[9]);
  EXPECT_TRUE(follower.gapOpen());
  ASSERT_TRUE(follower.snapshot(9, f.snapshots[8]).has_value());  // the one that covers it
  EXPECT_FALSE(follower.gapOpen());
  expectSame(f.classification[9], follower.held());
}

TEST(MapFollower, KeepingFewUpdatesOnlyNewerSnapshotsFillTheGap)
{
  const Flight f(12);
  MapFollower follower(f.mapper.resolution(), 2);
  for (std::uint64_t seq = 5; seq <= 10; ++seq) {  // joined at 5; only 9 and 10 are kept
    follower.update(seq, f.changes[seq - 1]);
  }
  EXPECT_FALSE(follower.snapshot(7, f.snapshots[6]).has_value());  // 8 was dropped: it cannot be rebuilt
  const auto diff = follower.snapshot(8, f.snapshots[7]);
  ASSERT_TRUE(diff.has_value());
  expectSame(f.classification[9], follower.held());
}

TEST(MapFollower, BadSnapshotBytesAreReportedAndChangeNothing)
{
  const Flight f(3);
  MapFollower follower(f.mapper.resolution());
  follower.update(2, f.changes[1]);
  bool bad = false;
  EXPECT_FALSE(follower.snapshot(2, {1, 2, 3, 4}, &bad).has_value());
  EXPECT_TRUE(bad);
  EXPECT_TRUE(follower.gapOpen());
}

}  // namespace
}  // namespace quad::mapping
