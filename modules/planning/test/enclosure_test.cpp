// SPDX-License-Identifier: BSD-3-Clause
// No path is an answer: which side known-occupied space seals off, against a full search.
#include <gtest/gtest.h>

#include <queue>
#include <random>
#include <unordered_set>

#include "quad/planning/dstar_lite.hpp"

namespace quad::planning {
namespace {

using geometry::VoxelGrid;

/// Every traversable cell reachable from c, by breadth-first search over the whole lattice.
std::unordered_set<Cell> component(const DStarLite& p, Cell c)
{
  std::unordered_set<Cell> seen;
  if (!p.traversable(c)) {
    return seen;
  }
  std::queue<Cell> open;
  open.push(c);
  seen.insert(c);
  std::vector<std::pair<Cell, double>> around;
  while (!open.empty()) {
    p.neighbours(open.front(), around);
    open.pop();
    for (const auto& [n, step] : around) {
      if (p.traversable(n) && seen.insert(n).second) {
        open.push(n);
      }
    }
  }
  return seen;
}

/// A hollow box of occupied voxels, walls one voxel thick, from lo to hi inclusive.
void hollowBox(DStarLite& p, const VoxelIndex& lo, const VoxelIndex& hi)
{
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int z = lo.z(); z <= hi.z(); ++z) {
        const bool shell = x == lo.x() || x == hi.x() || y == lo.y() || y == hi.y() || z == lo.z() || z == hi.z();
        if (shell) {
          p.updateVoxel(VoxelIndex(x, y, z), Occupancy::kOccupied);
        }
      }
    }
  }
}

TEST(Enclosure, TheStatusAgreesWithAFullSearchOnRandomWorlds)
{
  // GIVEN random worlds of boxes, some with a sealed room around the goal or the start,
  // unknown space traversable, seeds fixed
  int ok = 0, goal_enclosed = 0, start_enclosed = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    std::mt19937_64 rng(seed);
    DStarLite planner(Lattice(VoxelGrid(1.0), Vector3(0, 0, 0), Vector3(20, 20, 8)), {26, true, 0.0});
    std::uniform_int_distribution<int> xy(0, 19), z(0, 7), size(1, 6);
    for (int k = 0; k < 12; ++k) {
      const VoxelIndex lo(xy(rng), xy(rng), z(rng));
      const VoxelIndex extent(size(rng), size(rng), size(rng));
      for (int x = 0; x < extent.x(); ++x) {
        for (int y = 0; y < extent.y(); ++y) {
          for (int h = 0; h < extent.z(); ++h) {
            planner.updateVoxel(lo + VoxelIndex(x, y, h), Occupancy::kOccupied);
          }
        }
      }
    }
    VoxelIndex start(1, 1, 1), goal(17, 17, 4);
    if (seed % 3 == 1) {
      hollowBox(planner, goal - VoxelIndex(2, 2, 2), goal + VoxelIndex(2, 2, 2));
    } else if (seed % 3 == 2) {
      hollowBox(planner, start - VoxelIndex(1, 1, 1), start + VoxelIndex(3, 2, 2));
    }
    for (const VoxelIndex& v : {start, goal}) {
      planner.updateVoxel(v, Occupancy::kFree);  // a box may have covered them
    }
    const Cell s = *planner.lattice().cell(start);
    const Cell g = *planner.lattice().cell(goal);
    if (!planner.traversable(s) || !planner.traversable(g)) {
      continue;
    }
    planner.setStart(s);
    planner.setGoal(g);
    // WHEN it plans
    const PlanResult r = planner.plan();
    // THEN the status is what a full search of both sides says
    const auto from_goal = component(planner, g);
    const auto from_start = component(planner, s);
    if (from_goal.count(s) != 0) {
      EXPECT_EQ(r.status, PlanStatus::kOk) << "seed " << seed;
      ++ok;
    } else if (from_goal.size() <= from_start.size()) {
      EXPECT_EQ(r.status, PlanStatus::kGoalEnclosed) << "seed " << seed;
      ++goal_enclosed;
    } else {
      EXPECT_EQ(r.status, PlanStatus::kStartEnclosed) << "seed " << seed;
      ++start_enclosed;
    }
  }
  // Every answer was exercised.
  EXPECT_GT(ok, 5);
  EXPECT_GT(goal_enclosed, 5);
  EXPECT_GT(start_enclosed, 5);
}

TEST(Enclosure, AGoalSealedInARoomIsToldWithoutSearchingTheBox)
{
  // GIVEN a 3 x 3 x 3 m room at 0.2 m in a 60 x 20 x 10 m box (1.5 million cells), its walls
  // known, the rest unknown
  DStarLite planner(Lattice(VoxelGrid(0.2), Vector3(0, 0, 0), Vector3(60, 20, 10)), {26, true, 0.0});
  const VoxelIndex centre(200, 50, 20);
  hollowBox(planner, centre - VoxelIndex(8, 8, 8), centre + VoxelIndex(8, 8, 8));
  planner.setStart(*planner.lattice().cell(VoxelIndex(5, 50, 10)));
  planner.setGoal(*planner.lattice().cell(centre));
  // WHEN it plans
  const PlanResult r = planner.plan();
  // THEN the goal is enclosed, found by exhausting the room alone (15^3 = 3,375 cells inside)
  EXPECT_EQ(r.status, PlanStatus::kGoalEnclosed);
  EXPECT_LE(r.expansions, 3375U);
  EXPECT_EQ(sealedIn(planner, *planner.lattice().cell(centre), *planner.lattice().cell(VoxelIndex(5, 50, 10))),
            *planner.lattice().cell(centre));
}

TEST(Enclosure, FloodsThatMeetMeanAPathExists)
{
  DStarLite planner(Lattice(VoxelGrid(1.0), Vector3(0, 0, 0), Vector3(10, 10, 2)), {6, true, 0.0});
  EXPECT_EQ(sealedIn(planner, *planner.lattice().cell(VoxelIndex(0, 0, 0)), *planner.lattice().cell(VoxelIndex(9, 9, 1))),
            std::nullopt);
}

}  // namespace
}  // namespace quad::planning
