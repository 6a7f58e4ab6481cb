// SPDX-License-Identifier: BSD-3-Clause
// One replan as the planning module makes it: the path starts at the vehicle, the follower may
// fly only what the map knows free and what the horizon reaches, and a new version is told
// from jitter of the vehicle's own point.
#include "quad/planning/replan.hpp"

#include <gtest/gtest.h>

#include "quad/geometry/inflation.hpp"
#include "quad/geometry/polyline.hpp"

namespace quad::planning {
namespace {

using geometry::VoxelGrid;

/// 0.2 m voxels over 20 x 6 x 5 m, every voxel of |y| <= 1 m and 1 <= z <= 3 m known free up to
/// x = `free_to` m, the rest unknown, the goal at (18, 0, 2).
struct Corridor {
  explicit Corridor(double free_to, double horizon = 8.0)
      : planner(Lattice(VoxelGrid(0.2), Vector3(-2, -3, 0), Vector3(20, 3, 5)), {26, true, 0.65})
  {
    const VoxelGrid& g = planner.lattice().grid();
    const VoxelIndex lo = g.toIndex(Vector3(-2, -1, 1));
    const VoxelIndex hi = g.toIndex(Vector3(free_to - 1e-9, 1, 3));
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int z = lo.z(); z <= hi.z(); ++z) {
          planner.updateVoxel(VoxelIndex(x, y, z), Occupancy::kFree);
        }
      }
    }
    planner.setGoal(*planner.lattice().cellAt(Vector3(18, 0, 2)));
    params.resolution = 0.2;
    params.planner = {26, true, 0.65};
    params.known_space.horizon = horizon;
    params.known_space.own_radius = 0.0;
  }
  DStarLite planner;
  PlanningParams params;
};

TEST(Replan, ThePathStartsAtTheVehicleAndIsFlownOnlyAsFarAsTheMapKnowsItFree)
{
  // GIVEN free space known up to x = 5 m, the vehicle between cell centres at x = 0.05
  Corridor c(5.0);
  const Vector3 vehicle(0.05, 0.03, 2.04);
  // WHEN it replans
  const Replan r = replanFrom(c.planner, vehicle, c.params);
  // THEN the path reaches the goal from the vehicle itself, and what may be flown ends at the
  // frontier, before the unknown
  ASSERT_EQ(r.result.status, PlanStatus::kOk);
  EXPECT_EQ(r.waypoints.front(), vehicle);
  EXPECT_LT((r.waypoints.back() - Vector3(18, 0, 2)).norm(), 0.2);
  ASSERT_TRUE(r.frontier.has_value());
  EXPECT_EQ(r.known_free, *r.frontier);
  EXPECT_LE(r.known_free, 5.0);
  EXPECT_GT(r.known_free, 4.0);
  EXPECT_LT(r.known_free, geometry::polylineLength(r.waypoints));
  ASSERT_TRUE(frontierPoint(r).has_value());
  EXPECT_NEAR(frontierPoint(r)->x(), vehicle.x() + r.known_free, 0.3);
}

TEST(Replan, WithEverythingKnownFreeTheHorizonBoundsWhatIsFlownAndWithoutAHorizonNothingDoes)
{
  Corridor bounded(20.0, 8.0);
  const Replan r = replanFrom(bounded.planner, Vector3(0, 0, 2), bounded.params);
  ASSERT_EQ(r.result.status, PlanStatus::kOk);
  EXPECT_DOUBLE_EQ(r.known_free, 8.0);
  ASSERT_TRUE(r.frontier.has_value());
  EXPECT_DOUBLE_EQ(*r.frontier, 8.0);

  Corridor unbounded(20.0, 0.0);
  const Replan all = replanFrom(unbounded.planner, Vector3(0, 0, 2), unbounded.params);
  ASSERT_EQ(all.result.status, PlanStatus::kOk);
  EXPECT_FALSE(all.frontier.has_value());
  EXPECT_DOUBLE_EQ(all.known_free, geometry::polylineLength(all.waypoints));
}

TEST(Replan, AVehicleBelowTheLatticePlansFromItsNearestCellByWayOfIt)
{
  // GIVEN a vehicle on the ground, below the lattice's first layer of cells
  Corridor c(20.0, 0.0);
  const Vector3 ground(0, 0, -1.0);
  const Replan r = replanFrom(c.planner, ground, c.params);
  // THEN the path starts at the vehicle and climbs to the nearest cell before it goes on
  ASSERT_EQ(r.result.status, PlanStatus::kOk);
  ASSERT_GE(r.waypoints.size(), 3U);
  EXPECT_EQ(r.waypoints[0], ground);
  EXPECT_EQ(r.waypoints[1], c.planner.lattice().centre(r.result.cells.front()));
  // AND a point that is no point plans from nowhere
  EXPECT_EQ(replanFrom(c.planner, Vector3(NAN, 0, 2), c.params).result.status, PlanStatus::kOutOfBounds);
}

TEST(Replan, ANewVersionIsAnotherPathOrAStartAVoxelAwayNotTheVehicleJittering)
{
  Corridor c(5.0);
  const Replan first = replanFrom(c.planner, Vector3(0, 0, 2), c.params);
  // The vehicle moved a few centimetres: the same path.
  const Replan again = replanFrom(c.planner, Vector3(0.04, 0.02, 2), c.params);
  EXPECT_FALSE(changedPath(again, first, c.params.resolution));
  EXPECT_FALSE(changedPath(first, first, c.params.resolution));
  // The map knows more: the stopping point moved on.
  Corridor farther(9.0);
  const Replan more = replanFrom(farther.planner, Vector3(0, 0, 2), farther.params);
  EXPECT_TRUE(changedPath(more, first, c.params.resolution));
  // A waypoint past the first moved by more than a voxel.
  Replan moved = first;
  moved.waypoints.back().y() += 0.5;
  EXPECT_TRUE(changedPath(moved, first, c.params.resolution));
  // The vehicle climbed by more than a voxel: a path that starts where it now is.
  Replan climbed = first;
  climbed.waypoints.front().z() += 0.25;
  ASSERT_LT((*frontierPoint(climbed) - *frontierPoint(first)).norm(), c.params.resolution);
  EXPECT_TRUE(changedPath(climbed, first, c.params.resolution));
  // Another status.
  Replan none = first;
  none.result.status = PlanStatus::kNoPath;
  EXPECT_TRUE(changedPath(none, first, c.params.resolution));
}

}  // namespace
}  // namespace quad::planning
