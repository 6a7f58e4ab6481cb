// SPDX-License-Identifier: BSD-3-Clause
// How far a path keeps to known-free space: against voxels laid out by hand.
#include "quad/planning/known_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quad/geometry/inflation.hpp"
#include "quad/geometry/polyline.hpp"

namespace quad::planning {
namespace {

using geometry::VoxelGrid;

/// A 0.2 m lattice, 20 m along x, with every voxel of |y|, |z − 2| <= `half` m known free up to
/// x = `free_to` m; the rest unknown.
DStarLite corridor(double free_to, double half = 1.0)
{
  DStarLite p(Lattice(VoxelGrid(0.2), Vector3(-2, -3, 0), Vector3(20, 3, 5)), {26, true, 0.65});
  const VoxelGrid& g = p.lattice().grid();
  const VoxelIndex lo = g.toIndex(Vector3(-2, -half, 2 - half));
  const VoxelIndex hi = g.toIndex(Vector3(free_to - 1e-9, half, 2 + half));
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int z = lo.z(); z <= hi.z(); ++z) {
        p.updateVoxel(VoxelIndex(x, y, z), Occupancy::kFree);
      }
    }
  }
  return p;
}

const std::vector<Vector3> kPath{Vector3(0, 0, 2), Vector3(6, 0, 2), Vector3(6, 0, 4), Vector3(18, 0, 2)};

TEST(KnownSpace, TheFrontierIsWhereTheCheckedBallFirstMeetsUnknownSpace)
{
  // GIVEN free space up to x = 5 m around a path along x
  const DStarLite p = corridor(5.0);
  KnownSpaceCheck check;
  check.radius = 0.2;
  check.own_radius = 0.0;
  // WHEN the path is checked
  const auto frontier = knownFreeLength(p, kPath, kPath.front(), check);
  // THEN it ends where the ball around the path's voxel reaches the first unknown voxel (one
  // voxel before x = 5), within a sampling step
  ASSERT_TRUE(frontier.has_value());
  EXPECT_GT(*frontier, 5.0 - 0.2 - 0.2 - 0.05);
  EXPECT_LE(*frontier, 5.0);
}

TEST(KnownSpace, AnOccupiedVoxelOnTheWayIsAFrontierToo)
{
  DStarLite p = corridor(20.0, 2.0);
  p.updateVoxel(p.lattice().grid().toIndex(Vector3(3.1, 0, 2)), Occupancy::kOccupied);
  KnownSpaceCheck check;
  check.own_radius = 0.0;
  const auto frontier = knownFreeLength(p, kPath, kPath.front(), check);
  ASSERT_TRUE(frontier.has_value());
  EXPECT_LT(*frontier, 3.0);
  EXPECT_GT(*frontier, 2.5);
}

TEST(KnownSpace, NothingWithinTheHorizonIsNoFrontier)
{
  // GIVEN all known free, the path's climb included; the horizon ends before the unknown
  const DStarLite p = corridor(20.0, 2.5);
  KnownSpaceCheck check;
  check.horizon = 8.0;
  EXPECT_EQ(knownFreeLength(p, kPath, kPath.front(), check), std::nullopt);
  // and a horizon past the end of the path: the whole path is checked, and found free
  check.horizon = 100.0;
  EXPECT_EQ(knownFreeLength(p, {Vector3(0, 0, 2), Vector3(10, 0, 2)}, Vector3(0, 0, 2), check), std::nullopt);
}

TEST(KnownSpace, TheVehiclesOwnVolumeCountsAsFree)
{
  // GIVEN nothing known at all
  const DStarLite p(Lattice(VoxelGrid(0.2), Vector3(-2, -3, 0), Vector3(20, 3, 5)), {26, true, 0.65});
  KnownSpaceCheck check;
  check.radius = 0.2;
  check.own_radius = 0.55;
  // WHEN checked from where the vehicle is
  const auto frontier = knownFreeLength(p, kPath, kPath.front(), check);
  // THEN the path is flyable only through its own volume: a few tenths of a metre
  ASSERT_TRUE(frontier.has_value());
  EXPECT_GT(*frontier, 0.05);
  EXPECT_LT(*frontier, 0.55);
}

TEST(KnownSpace, AVehicleTakingOverInTheAirSetsOffThoughItsCameraNeverSawBehindIt)
{
  // GIVEN everything known free but the space behind a vehicle (x < 0) that started in the air
  // looking along +x, off the centre of its voxel; the tube and own radius of planning_params
  const DStarLite p = corridor(20.0, 2.5);
  DStarLite unseen(Lattice(VoxelGrid(0.2), Vector3(-2, -3, 0), Vector3(20, 3, 5)), {26, true, 0.65});
  const VoxelGrid& g = unseen.lattice().grid();
  for (int x = g.toIndex(Vector3(0.0, 0, 0)).x(); x <= g.toIndex(Vector3(20.0 - 1e-9, 0, 0)).x(); ++x) {
    for (int y = g.toIndex(Vector3(0, -2.5, 0)).y(); y <= g.toIndex(Vector3(0, 2.5, 0)).y(); ++y) {
      for (int z = g.toIndex(Vector3(0, 0, 0.5)).z(); z <= g.toIndex(Vector3(0, 0, 4.5)).z(); ++z) {
        unseen.updateVoxel(VoxelIndex(x, y, z), Occupancy::kFree);
      }
    }
  }
  KnownSpaceCheck check;
  check.radius = 0.45;
  check.own_radius = 0.45 + 0.5 * std::sqrt(3.0) * 0.2;
  check.horizon = 8.0;
  const Vector3 at(0.15, 0.05, 2.05);
  // (the tube read round its voxel reaches unseen voxels past the own radius)
  bool reaches = false;
  for (const VoxelIndex& o : geometry::inflationOffsets(check.radius, g.resolution())) {
    const VoxelIndex u = g.toIndex(at) + o;
    reaches = reaches || (unseen.voxelState(u) != Occupancy::kFree && (g.centre(u) - at).norm() > check.own_radius);
  }
  ASSERT_TRUE(reaches);
  // WHEN a path leads ahead from where it hovers
  const std::vector<Vector3> ahead{at, Vector3(10.0, 0.05, 2.05)};
  // THEN it is known free as far as the horizon, as where everything is known
  EXPECT_EQ(knownFreeLength(unseen, ahead, at, check), std::nullopt);
  EXPECT_EQ(knownFreeLength(p, ahead, at, check), std::nullopt);
}

/// Known free space all round, but for a wall of occupied voxels whose face is at y = 0.4 m;
/// checked with the tube and own radius of a 0.35 m vehicle with a 0.1 m margin on 0.2 m
/// voxels (planning_params).
DStarLite besideAWall(KnownSpaceCheck& check)
{
  DStarLite p = corridor(20.0, 2.5);
  const VoxelGrid& g = p.lattice().grid();
  const VoxelIndex lo = g.toIndex(Vector3(-2, 0.5, 0.5));
  const VoxelIndex hi = g.toIndex(Vector3(6, 1.5, 3.5));
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int z = lo.z(); z <= hi.z(); ++z) {
        p.updateVoxel(VoxelIndex(x, y, z), Occupancy::kOccupied);
      }
    }
  }
  check.radius = 0.45;
  check.own_radius = 0.45 + 0.5 * std::sqrt(3.0) * 0.2;
  return p;
}

TEST(KnownSpace, AVehicleStoppedBesideAnObstacleCanLeaveItButNotNearIt)
{
  // GIVEN a vehicle of radius 0.35 m stopped 0.04 m from a wall's face
  KnownSpaceCheck check;
  const DStarLite p = besideAWall(check);
  const Vector3 at(2.0, 0.01, 2.0);
  // WHEN a path leads away from the wall
  const auto away = knownFreeLength(p, {at, Vector3(2.0, -1.5, 2.0), Vector3(8.0, -1.5, 2.0)}, at, check);
  // THEN it is known free beyond the vehicle's own voxel (before, the wall read round that
  // voxel made every frontier 0: the vehicle never moved again)
  EXPECT_TRUE(!away || *away > 0.5) << *away;
  // AND a path towards the wall or along it is known free no further than that voxel
  for (const Vector3& to : {Vector3(2.0, 0.3, 2.0), Vector3(4.0, 0.01, 2.0), Vector3(3.0, 0.3, 2.0)}) {
    const auto frontier = knownFreeLength(p, {at, to}, at, check);
    ASSERT_TRUE(frontier.has_value()) << to.transpose();
    EXPECT_LT(*frontier, 0.3) << to.transpose();
  }
}

TEST(KnownSpace, ThePathUpToTheFrontierNeverMeetsAVoxelThePolicyForbids)
{
  // GIVEN random seeded maps (free, occupied and unknown voxels in blobs) and random paths
  const VoxelGrid grid(0.2);
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    DStarLite p(Lattice(grid, Vector3(0, 0, 0), Vector3(12, 12, 6)), {26, true, 0.5});
    std::uniform_real_distribution<double> x(0.5, 11.5), z(0.5, 5.5), r(0.3, 2.5);
    for (int k = 0; k < 30; ++k) {
      const Vector3 c(x(rng), x(rng), z(rng));
      const double radius = r(rng);
      const Occupancy state = k % 6 == 5 ? Occupancy::kOccupied : (k % 6 == 4 ? Occupancy::kUnknown : Occupancy::kFree);
      const VoxelIndex lo = grid.toIndex(c - Vector3::Constant(radius));
      const VoxelIndex hi = grid.toIndex(c + Vector3::Constant(radius));
      for (int i = lo.x(); i <= hi.x(); ++i) {
        for (int j = lo.y(); j <= hi.y(); ++j) {
          for (int h = lo.z(); h <= hi.z(); ++h) {
            if ((grid.centre(VoxelIndex(i, j, h)) - c).norm() <= radius) {
              p.updateVoxel(VoxelIndex(i, j, h), state);
            }
          }
        }
      }
    }
    std::vector<Vector3> path;
    for (int k = 0; k < 4; ++k) {
      path.emplace_back(x(rng), x(rng), z(rng));
    }
    KnownSpaceCheck check;
    check.horizon = 100.0;
    check.own_radius = 0.3;
    // WHEN the frontier is found
    const auto frontier = knownFreeLength(p, path, path.front(), check);
    // THEN every point before it, sampled finely, has only known-free voxels (or the vehicle's
    // own) within the checked ball, or lies in the vehicle's voxel; and when there is
    // one, a forbidden voxel lies just past it
    const auto ball = geometry::inflationOffsets(check.radius, grid.resolution());
    const auto allowed = [&](const Vector3& point) {
      const VoxelIndex v = grid.toIndex(point);
      const bool own = v == grid.toIndex(path.front());
      for (const VoxelIndex& d : ball) {
        const Occupancy state = p.voxelState(v + d);
        if (state != Occupancy::kFree && !own &&
            (grid.centre(v + d) - path.front()).norm() > check.own_radius) {
          return false;
        }
      }
      return true;
    };
    const double length = geometry::polylineLength(path);
    const double end = frontier ? *frontier : length;
    for (double s = 0.0; s < end; s += 0.01) {
      ASSERT_TRUE(allowed(geometry::pointAlong(path, s))) << "seed " << seed << " at " << s << " of " << end;
    }
    if (frontier) {
      bool forbidden = false;
      for (double s = *frontier; s <= *frontier + 0.1 && !forbidden; s += 0.005) {
        forbidden = !allowed(geometry::pointAlong(path, s));
      }
      EXPECT_TRUE(forbidden) << "seed " << seed << ": nothing forbidden just past the frontier at " << *frontier;
    }
  }
}

}  // namespace
}  // namespace quad::planning
