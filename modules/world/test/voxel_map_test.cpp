// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/voxel_map.hpp"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <random>

#include "quad/world/world.hpp"

namespace quad::world {
namespace {

constexpr double kRes = 0.1;

/// A wall of voxels x ∈ [2.0, 2.3), y ∈ [−1, 1), z ∈ [0, 2).
VoxelMap wall()
{
  std::vector<VoxelIndex> v;
  for (int z = 0; z < 20; ++z) {
    for (int y = -10; y < 10; ++y) {
      for (int x = 20; x < 23; ++x) {
        v.emplace_back(x, y, z);
      }
    }
  }
  return VoxelMap("wall", geometry::VoxelGrid(kRes), v);
}

/// Random voxels in a 4 m cube, seeded.
std::vector<VoxelIndex> randomVoxels(std::mt19937_64& rng, int count)
{
  std::uniform_int_distribution<int> idx(-20, 19);
  std::vector<VoxelIndex> v;
  for (int i = 0; i < count; ++i) {
    v.emplace_back(idx(rng), idx(rng), idx(rng));
  }
  return v;
}

Vector3 randomDirection(std::mt19937_64& rng)
{
  std::normal_distribution<double> n;
  return Vector3(n(rng), n(rng), n(rng)).normalized();
}

/// The reference: every occupied voxel's box tested (slab test), the nearest entry kept.
std::optional<double> bruteRaycast(const VoxelMap& m, const Vector3& o, const Vector3& d, double t_max)
{
  std::optional<double> best;
  for (const VoxelIndex& v : m.occupiedVoxels()) {
    const Vector3 lo = v.cast<double>() * m.resolution();
    const Vector3 hi = lo + Vector3::Constant(m.resolution());
    double t0 = 0.0;
    double t1 = t_max;
    for (int a = 0; a < 3; ++a) {
      double n = (lo[a] - o[a]) / d[a];
      double f = (hi[a] - o[a]) / d[a];
      if (n > f) {
        std::swap(n, f);
      }
      t0 = std::max(t0, n);
      t1 = std::min(t1, f);
    }
    if (t0 <= t1 && (!best || t0 < *best)) {
      best = t0;
    }
  }
  return best;
}

TEST(VoxelMap, KeepsEachOccupiedVoxelOnceAndSpansTheirBox)
{
  const VoxelMap m("twice", geometry::VoxelGrid(kRes), {{1, 2, 3}, {1, 2, 3}, {-4, 0, 5}});
  EXPECT_EQ(m.occupiedVoxels().size(), 2U);
  EXPECT_TRUE(m.occupied({1, 2, 3}));
  EXPECT_TRUE(m.occupied({-4, 0, 5}));
  EXPECT_FALSE(m.occupied({0, 2, 3}));
  EXPECT_FALSE(m.occupied({100, 2, 3}));  // outside the box
  Vector3 lo, hi;
  m.bounds(lo, hi);
  EXPECT_TRUE(lo.isApprox(Vector3(-0.4, 0.0, 0.3)));
  EXPECT_TRUE(hi.isApprox(Vector3(0.2, 0.3, 0.6)));
  EXPECT_THROW(VoxelMap("empty", geometry::VoxelGrid(kRes), {}), std::invalid_argument);
  EXPECT_THROW(VoxelMap("huge", geometry::VoxelGrid(kRes), {{0, 0, 0}, {2000, 2000, 2000}}), std::invalid_argument);
}

TEST(VoxelMap, RayHitsTheWallAtTheExactDistance)
{
  const VoxelMap m = wall();
  // GIVEN a ray along x at mid-height  THEN  it enters the wall's face at x = 2
  EXPECT_NEAR(*m.raycast(Vector3(0, 0.05, 1.05), Vector3::UnitX(), 10.0), 2.0, 1e-12);
  // at 45° in x–y: the face x = 2 is √2·2 away
  EXPECT_NEAR(*m.raycast(Vector3(0, -1.95, 1.05), Vector3(1, 1, 0).normalized(), 10.0), 2.0 * std::sqrt(2.0), 1e-12);
  // from behind, along −x: the back face x = 2.3
  EXPECT_NEAR(*m.raycast(Vector3(5, 0.05, 1.05), -Vector3::UnitX(), 10.0), 2.7, 1e-12);
  // from inside: 0
  EXPECT_DOUBLE_EQ(*m.raycast(Vector3(2.15, 0.05, 1.05), Vector3::UnitY(), 10.0), 0.0);
  // above the wall, short of it, or pointing away: nothing
  EXPECT_FALSE(m.raycast(Vector3(0, 0.05, 2.05), Vector3::UnitX(), 10.0));
  EXPECT_FALSE(m.raycast(Vector3(0, 0.05, 1.05), Vector3::UnitX(), 1.99));
  EXPECT_FALSE(m.raycast(Vector3(0, 0.05, 1.05), -Vector3::UnitX(), 10.0));
}

TEST(VoxelMap, MarchedRaysAgreeWithTestingEveryVoxel)
{
  std::mt19937_64 rng(11);
  const VoxelMap m("random", geometry::VoxelGrid(kRes), randomVoxels(rng, 600));
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vector3 o(u(rng), u(rng), u(rng));
    const Vector3 d = randomDirection(rng);
    const auto fast = m.raycast(o, d, 6.0);
    const auto slow = bruteRaycast(m, o, d, 6.0);
    ASSERT_EQ(fast.has_value(), slow.has_value()) << "ray " << i;
    if (fast) {
      EXPECT_NEAR(*fast, *slow, 1e-9) << "ray " << i;
      ++hits;
    }
  }
  EXPECT_GT(hits, 300);  // the comparison covers hits as well as misses
}

TEST(VoxelMap, MarchedRaysStopInTheVoxelOctoMapsCastRayStopsIn)
{
  // GIVEN the same voxels in an OcTree  WHEN  rays start in free space  THEN  OctoMap's own
  // castRay ends in the voxel our ray enters first.
  std::mt19937_64 rng(5);
  const std::vector<VoxelIndex> voxels = randomVoxels(rng, 800);
  const VoxelMap m("random", geometry::VoxelGrid(kRes), voxels);
  octomap::OcTree tree(kRes);
  for (const VoxelIndex& v : voxels) {
    const Vector3 c = m.grid().centre(v);
    tree.updateNode(octomap::point3d(static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())), true);
  }
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  int compared = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vector3 o(u(rng), u(rng), u(rng));
    if (m.occupied(m.grid().toIndex(o))) {
      continue;
    }
    const Vector3 d = randomDirection(rng);
    const auto ours = m.raycast(o, d, 5.0);
    octomap::point3d end;
    const bool theirs = tree.castRay(octomap::point3d(static_cast<float>(o.x()), static_cast<float>(o.y()), static_cast<float>(o.z())),
                                     octomap::point3d(static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())),
                                     end, true, 5.0);
    if (!ours || !theirs) {
      // OctoMap stops within max range of the origin's voxel centre, not the origin: compare
      // only rays that clearly end (or not) inside the range
      if (ours && *ours < 4.8) {
        ADD_FAILURE() << "ray " << i << ": ours hits at " << *ours << ", OctoMap's misses";
      }
      continue;
    }
    const VoxelIndex ours_voxel = m.grid().toIndex(o + (*ours + 1e-9) * d);
    const VoxelIndex theirs_voxel = m.grid().toIndex(Vector3(end.x(), end.y(), end.z()));
    EXPECT_EQ(ours_voxel, theirs_voxel) << "ray " << i;
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

TEST(VoxelMap, DistanceIsTheNearestVoxelsWithinTheCap)
{
  std::mt19937_64 rng(3);
  const VoxelMap m("random", geometry::VoxelGrid(kRes), randomVoxels(rng, 50));
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 500; ++i) {
    const Vector3 p(u(rng), u(rng), u(rng));
    double nearest = std::numeric_limits<double>::infinity();
    for (const VoxelIndex& v : m.occupiedVoxels()) {
      const Vector3 lo = v.cast<double>() * kRes;
      nearest = std::min(nearest, (lo - p).cwiseMax(p - lo - Vector3::Constant(kRes)).cwiseMax(0.0).norm());
    }
    const auto d = m.distance(p, 1.0);
    if (nearest <= 1.0) {
      ASSERT_TRUE(d.has_value()) << "point " << i;
      EXPECT_NEAR(*d, nearest, 1e-12) << "point " << i;
    } else {
      EXPECT_FALSE(d.has_value()) << "point " << i;
    }
  }
}

TEST(VoxelMap, AWorldCountsItsMapsInContactsRaysAndClearance)
{
  // GIVEN a world with one box and the wall map
  const World w(Bounds{Vector3(-5, -5, 0), Vector3(5, 5, 5)}, Vector3::Zero(), Vector3(1, 0, 1),
                {Obstacle::makeBox({Vector3(-3, 0, 1), Vector3(1, 1, 2), 0.0})}, 0.0, {wall()});
  const int map = w.mapId(0);
  EXPECT_EQ(map, 1);
  EXPECT_EQ(w.describe(map), "map 0 (wall)");
  // THEN a sphere touching the wall is in contact with the map, and only with it
  EXPECT_EQ(w.contacts(Vector3(1.75, 0, 1), 0.3), std::vector<int>{map});
  EXPECT_TRUE(w.contacts(Vector3(1.65, 0, 1), 0.3).empty());
  // a ray meets the map before the box behind it, and the box when looking the other way
  const auto hit = w.raycast(Vector3(0, 0.05, 1.05), Vector3::UnitX(), 10.0);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->obstacle, map);
  EXPECT_NEAR(hit->distance, 2.0, 1e-12);
  EXPECT_EQ(w.raycast(Vector3(0, 0.05, 1.05), -Vector3::UnitX(), 10.0)->obstacle, 0);
  // the nearest: the nearer of the two
  EXPECT_NEAR(w.nearest(Vector3(1.5, 0, 1), 0.3, 5.0)->distance, 0.5, 1e-12);
  EXPECT_EQ(w.nearest(Vector3(1.5, 0, 1), 0.3, 5.0)->id, map);
  EXPECT_NEAR(w.nearest(Vector3(-1.0, 0, 1), 0.3, 5.0)->distance, 1.5, 1e-12);
  EXPECT_EQ(w.nearest(Vector3(-1.0, 0, 1), 0.3, 5.0)->id, 0);
  EXPECT_FALSE(w.nearest(Vector3(0.5, 3, 4.5), 0.3, 0.2));  // nothing within the cap
}

TEST(VoxelMap, WhatTheVehicleStandsOnIsContactNotCollision)
{
  // GIVEN a slab 3 m up (x, y in [−2, 2), one voxel thick) with a 1 m hole at x, y in
  // [1, 2), a box standing on the ground and a pillar through the slab
  std::vector<VoxelIndex> slab;
  for (int y = -20; y < 20; ++y) {
    for (int x = -20; x < 20; ++x) {
      if (x < 10 || y < 10) {
        slab.emplace_back(x, y, 29);
      }
    }
  }
  for (int z = 30; z < 40; ++z) {
    slab.emplace_back(-15, -15, z);  // the pillar above the slab
  }
  const World w(Bounds{Vector3(-5, -5, 0), Vector3(5, 5, 6)}, Vector3::Zero(), Vector3(1, 0, 1),
                {Obstacle::makeBox({Vector3(3.5, 3.5, 0.5), Vector3(1, 1, 1), 0.0})}, 0.0,
                {VoxelMap("slab", geometry::VoxelGrid(kRes), slab)});
  const double r = 0.2;
  // THEN the support is the slab's top above it, the ground under the slab and in its hole,
  // the box's top above the box
  EXPECT_NEAR(w.supportHeight(Vector3(0, 0, 3.5), r), 3.0, 1e-12);
  EXPECT_NEAR(w.supportHeight(Vector3(0, 0, 3.0), r), 3.0, 1e-12);  // standing on it
  EXPECT_DOUBLE_EQ(w.supportHeight(Vector3(0, 0, 2.5), r), 0.0);
  EXPECT_DOUBLE_EQ(w.supportHeight(Vector3(1.5, 1.5, 3.5), r), 0.0);  // over the hole
  EXPECT_NEAR(w.supportHeight(Vector3(0.95, 1.5, 3.5), r), 3.0, 1e-12);  // its edge within r/2
  EXPECT_DOUBLE_EQ(w.supportHeight(Vector3(3.5, 3.5, 2.0), r), 1.0);
  // resting on the slab or the box touches nothing; the pillar beside the vehicle does
  EXPECT_TRUE(w.contacts(Vector3(0, 0, 3.0), r).empty());
  EXPECT_TRUE(w.contacts(Vector3(3.5, 3.5, 1.0), r).empty());
  EXPECT_EQ(w.contacts(Vector3(-1.25, -1.45, 3.0), r), std::vector<int>{w.mapId(0)});
  EXPECT_FALSE(w.nearest(Vector3(0, 0, 3.0), r, r));
  // flying up into the slab from below is a collision
  EXPECT_EQ(w.contacts(Vector3(0, 0, 2.85), r), std::vector<int>{w.mapId(0)});
}

}  // namespace
}  // namespace quad::world
