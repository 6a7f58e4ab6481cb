// SPDX-License-Identifier: BSD-3-Clause
// D* Lite against Dijkstra from scratch, and the ways D* Lite implementations are known to fail.
#include "quad/planning/dstar_lite.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace quad::planning {
namespace {

using geometry::VoxelGrid;

Lattice box(int nx, int ny, int nz)
{
  // Resolution 1 m, voxel centres 0.5 ... n − 0.5.
  return Lattice(VoxelGrid(1.0), Vector3(0, 0, 0), Vector3(nx, ny, nz));
}

Cell at(const DStarLite& p, int x, int y, int z) { return *p.lattice().cell(VoxelIndex(x, y, z)); }

/// The path is traversable, visits no cell twice, and its steps add up to the cost reported.
void expectCollisionFree(const DStarLite& p, const PlanResult& r)
{
  std::set<Cell> seen;
  double length = 0.0;
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    EXPECT_TRUE(p.traversable(r.cells[i])) << "cell " << r.cells[i];
    EXPECT_TRUE(seen.insert(r.cells[i]).second) << "revisits cell " << r.cells[i];  // no oscillation
    if (i > 0) {
      const double step = p.edgeCost(r.cells[i - 1], r.cells[i]);
      EXPECT_LT(step, kInfinity);
      length += step;
    }
  }
  if (r.status == PlanStatus::kOk) {
    EXPECT_NEAR(length, r.cost, 1e-9);
  }
}

TEST(DStarLite, CostEqualsDijkstraAfterEveryBatchOfUpdatesWithAMovingStart)
{
  for (const Heuristic heuristic : {Heuristic::kLattice, Heuristic::kEuclidean}) {
    for (const int connectivity : {6, 18, 26}) {
      std::mt19937_64 rng(2024 + static_cast<unsigned>(connectivity));
      DStarLite planner(box(24, 24, 6), {connectivity, true, 0.0, heuristic});
      Cell start = at(planner, 0, 0, 0);
      const Cell goal = at(planner, 23, 23, 5);
      planner.setStart(start);
      planner.setGoal(goal);
      std::uniform_int_distribution<int> x(0, 23), z(0, 5);
      for (int batch = 0; batch < 30; ++batch) {
        for (int k = 0; k < 25; ++k) {
          const VoxelIndex v(x(rng), x(rng), z(rng));
          if (planner.lattice().cell(v) == goal || planner.lattice().cell(v) == start) {
            continue;
          }
          planner.updateVoxel(v, rng() % 5 == 0 ? Occupancy::kFree : Occupancy::kOccupied);
        }
        const PlanResult r = planner.plan();
        const double reference = shortestPathCost(planner, start, goal);
        if (reference == kInfinity) {
          EXPECT_TRUE(r.status == PlanStatus::kGoalEnclosed || r.status == PlanStatus::kStartEnclosed)
              << toString(r.status);
          continue;
        }
        ASSERT_EQ(r.status, PlanStatus::kOk) << "connectivity " << connectivity << " batch " << batch;
        EXPECT_NEAR(r.cost, reference, 1e-9) << "connectivity " << connectivity << " batch " << batch;
        expectCollisionFree(planner, r);
        // Move the start two cells along the path, as the vehicle would.
        if (r.cells.size() > 3) {
          start = r.cells[2];
          planner.setStart(start);
        }
      }
    }
  }
}

TEST(DStarLite, CostEqualsDijkstraWhileMovingKeepOutsComeAndGoOverAMap)
{
  // A block of kept-out cells moves across the box each replan, as another vehicle's tube
  // would, over a map of random obstacles; the search is repaired, never restarted.
  std::mt19937_64 rng(77);
  DStarLite planner(box(20, 20, 5), {26, true, 0.0, Heuristic::kLattice});
  Cell start = at(planner, 0, 0, 1);
  const Cell goal = at(planner, 19, 19, 2);
  planner.setStart(start);
  planner.setGoal(goal);
  std::uniform_int_distribution<int> x(0, 19), z(0, 4);
  for (int k = 0; k < 120; ++k) {
    const VoxelIndex v(x(rng), x(rng), z(rng));
    if (planner.lattice().cell(v) != goal && planner.lattice().cell(v) != start) {
      planner.updateVoxel(v, Occupancy::kOccupied);
    }
  }
  for (int step = 0; step < 16; ++step) {
    std::vector<Cell> keep_out;
    for (int bx = 0; bx < 4; ++bx) {
      for (int by = 0; by < 3; ++by) {
        for (int bz = 0; bz < 5; ++bz) {
          const auto c = planner.lattice().cell(VoxelIndex(2 + step + bx, 8 + by, bz));
          if (c && *c != goal && *c != start) {
            keep_out.push_back(*c);
          }
        }
      }
    }
    planner.setKeepOut(step == 15 ? std::vector<Cell>{} : keep_out);
    if (step < 15) {
      for (const Cell c : keep_out) {
        EXPECT_FALSE(planner.traversable(c));
      }
    }
    EXPECT_TRUE(std::is_sorted(planner.keepOut().begin(), planner.keepOut().end()));
    const PlanResult r = planner.plan();
    const double reference = shortestPathCost(planner, start, goal);
    ASSERT_NE(reference, kInfinity) << "step " << step;
    ASSERT_EQ(r.status, PlanStatus::kOk) << "step " << step;
    EXPECT_NEAR(r.cost, reference, 1e-9) << "step " << step;
    expectCollisionFree(planner, r);
    if (r.cells.size() > 3) {
      start = r.cells[1];
      planner.setStart(start);
    }
  }
  // With the keep-out gone, the map alone decides: what a planner that never had one plans.
  DStarLite fresh(box(20, 20, 5), {26, true, 0.0, Heuristic::kLattice});
  std::mt19937_64 again(77);
  for (int k = 0; k < 120; ++k) {
    const VoxelIndex v(x(again), x(again), z(again));
    if (fresh.lattice().cell(v) != goal && fresh.lattice().cell(v) != at(fresh, 0, 0, 1)) {
      fresh.updateVoxel(v, Occupancy::kOccupied);
    }
  }
  fresh.setStart(start);
  fresh.setGoal(goal);
  EXPECT_NEAR(fresh.plan().cost, planner.plan().cost, 1e-9);
}

TEST(DStarLite, LatticeHeuristicIsTheObstacleFreeDistanceAndAConsistentLowerBound)
{
  for (const int connectivity : {6, 18, 26}) {
    // GIVEN an empty lattice and the same lattice with seeded obstacles
    DStarLite empty(box(7, 7, 7), {connectivity, true, 0.0});
    DStarLite cluttered(box(7, 7, 7), {connectivity, true, 0.0});
    DStarLite euclidean(box(7, 7, 7), {connectivity, true, 0.0, Heuristic::kEuclidean});
    std::mt19937_64 rng(77 + static_cast<unsigned>(connectivity));
    std::uniform_int_distribution<int> u(0, 6);
    for (int k = 0; k < 60; ++k) {
      cluttered.updateVoxel(VoxelIndex(u(rng), u(rng), u(rng)), Occupancy::kOccupied);
    }
    std::vector<std::pair<Cell, double>> around;
    for (int k = 0; k < 200; ++k) {
      const Cell a = at(empty, u(rng), u(rng), u(rng));
      const Cell b = at(empty, u(rng), u(rng), u(rng));
      // THEN it is the shortest path where nothing is in the way, never longer than one that
      // has to go around, never shorter than the straight line's heuristic
      EXPECT_NEAR(empty.heuristic(a, b), shortestPathCost(empty, a, b), 1e-9) << connectivity;
      if (cluttered.traversable(a) && cluttered.traversable(b)) {
        EXPECT_LE(cluttered.heuristic(a, b), shortestPathCost(cluttered, a, b) + 1e-9) << connectivity;
      }
      EXPECT_LE(euclidean.heuristic(a, b), empty.heuristic(a, b) + 1e-12) << connectivity;
      // AND consistent: one step never lowers it by more than the step costs
      empty.neighbours(a, around);
      for (const auto& [n, step] : around) {
        EXPECT_LE(empty.heuristic(a, b), step + empty.heuristic(n, b) + 1e-12) << connectivity;
      }
    }
  }
}

TEST(DStarLite, PathIsFoundWheneverOneExistsWithInflationAndAWanderingStart)
{
  // As the planning node drives it: obstacles inflated by a radius, revealed in batches,
  // and a start that goes where the vehicle is (near the path, not on it), escaping
  // blocked cells to the nearest free one.
  for (const std::uint64_t seed : {1U, 2U, 3U, 4U, 5U, 6U}) {
    std::mt19937_64 rng(seed);
    DStarLite planner(Lattice(VoxelGrid(0.2), Vector3(-1, -2, 0), Vector3(12, 2, 3)), {26, true, 0.45});
    const Cell goal = *planner.lattice().cellAt(Vector3(11, 0, 1.5));
    Vector3 position(0, 0, 1.5);
    planner.setGoal(goal);
    std::uniform_real_distribution<double> ox(1.0, 11.0), oy(-2.0, 2.0), oz(0.0, 3.0), jitter(-0.15, 0.15);
    for (int step = 0; step < 60; ++step) {
      for (int k = 0; k < 6; ++k) {
        const auto v = planner.lattice().grid().toIndex(Vector3(ox(rng), oy(rng), oz(rng)));
        if ((planner.lattice().grid().centre(v) - Vector3(11, 0, 1.5)).norm() > 1.0) {
          planner.updateVoxel(v, Occupancy::kOccupied);
        }
      }
      auto start = planner.lattice().cellAt(position);
      ASSERT_TRUE(start);
      if (!planner.traversable(*start)) {
        start = planner.nearestTraversable(*start, 1.2).value_or(*start);
      }
      planner.setStart(*start);
      const PlanResult r = planner.plan();
      const double reference = shortestPathCost(planner, *start, goal);
      if (reference == kInfinity || !planner.traversable(*start)) {
        continue;
      }
      ASSERT_EQ(r.status, PlanStatus::kOk) << "seed " << seed << " step " << step << " cost " << r.cost;
      EXPECT_NEAR(r.cost, reference, 1e-9) << "seed " << seed << " step " << step;
      expectCollisionFree(planner, r);
      // The vehicle moves a little along the path, off its cells' centres.
      const std::size_t next = std::min<std::size_t>(r.cells.size() - 1, 2);
      position = planner.lattice().centre(r.cells[next]) + Vector3(jitter(rng), jitter(rng), jitter(rng));
    }
  }
}

TEST(DStarLite, InflationBlocksCellsWithinTheRadius)
{
  DStarLite planner(box(10, 10, 3), {26, true, 1.2});
  planner.updateVoxel(VoxelIndex(5, 5, 1), Occupancy::kOccupied);
  EXPECT_FALSE(planner.traversable(at(planner, 5, 5, 1)));
  EXPECT_FALSE(planner.traversable(at(planner, 6, 5, 1)));   // 0.5 m from the box
  EXPECT_FALSE(planner.traversable(at(planner, 6, 6, 1)));   // 0.71 m
  EXPECT_FALSE(planner.traversable(at(planner, 6, 5, 2)));   // 0.71 m, a layer up
  EXPECT_TRUE(planner.traversable(at(planner, 7, 5, 1)));    // 1.5 m from the box: clear of 1.2 m
  planner.updateVoxel(VoxelIndex(5, 5, 1), Occupancy::kFree);
  EXPECT_TRUE(planner.traversable(at(planner, 6, 5, 1)));    // cleared again, incrementally
}

TEST(DStarLiteRegression, StartEqualsGoal)
{
  DStarLite planner(box(5, 5, 1), {});
  planner.setStart(at(planner, 2, 2, 0));
  planner.setGoal(at(planner, 2, 2, 0));
  const PlanResult r = planner.plan();
  EXPECT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(r.cost, 0.0);
  EXPECT_EQ(r.cells.size(), 1U);
}

TEST(DStarLiteRegression, OneCellGapInAWallIsFound)
{
  for (const int connectivity : {6, 26}) {
    DStarLite planner(box(9, 9, 1), {connectivity, true, 0.0});
    for (int y = 0; y < 9; ++y) {
      if (y != 6) {
        planner.updateVoxel(VoxelIndex(4, y, 0), Occupancy::kOccupied);  // wall x = 4, gap at y = 6
      }
    }
    planner.setStart(at(planner, 0, 0, 0));
    planner.setGoal(at(planner, 8, 0, 0));
    const PlanResult r = planner.plan();
    ASSERT_EQ(r.status, PlanStatus::kOk) << connectivity;
    EXPECT_NE(std::find(r.cells.begin(), r.cells.end(), at(planner, 4, 6, 0)), r.cells.end());
    EXPECT_NEAR(r.cost, shortestPathCost(planner, at(planner, 0, 0, 0), at(planner, 8, 0, 0)), 1e-9);
  }
}

TEST(DStarLiteRegression, OneCellWallWithNoGapHasNoPathAndNoDiagonalLeak)
{
  DStarLite planner(box(9, 9, 1), {26, true, 0.0});
  for (int y = 0; y < 9; ++y) {
    planner.updateVoxel(VoxelIndex(4, y, 0), Occupancy::kOccupied);
  }
  planner.setStart(at(planner, 0, 0, 0));
  planner.setGoal(at(planner, 8, 0, 0));
  // Two halves of 36 cells each: a tie goes to the goal's side.
  EXPECT_EQ(planner.plan().status, PlanStatus::kGoalEnclosed);
}

TEST(DStarLiteRegression, ReplanningAfterTheStartMoved)
{
  DStarLite planner(box(12, 12, 1), {26, true, 0.0});
  planner.setStart(at(planner, 0, 0, 0));
  planner.setGoal(at(planner, 11, 11, 0));
  ASSERT_EQ(planner.plan().status, PlanStatus::kOk);
  planner.setStart(at(planner, 5, 0, 0));
  planner.updateVoxel(VoxelIndex(6, 1, 0), Occupancy::kOccupied);
  const PlanResult r = planner.plan();
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_EQ(r.cells.front(), at(planner, 5, 0, 0));
  EXPECT_NEAR(r.cost, shortestPathCost(planner, at(planner, 5, 0, 0), at(planner, 11, 11, 0)), 1e-9);
}

TEST(DStarLiteRegression, GoalBlockedThenUnblocked)
{
  DStarLite planner(box(8, 8, 1), {26, true, 0.0});
  planner.setStart(at(planner, 0, 0, 0));
  planner.setGoal(at(planner, 7, 7, 0));
  ASSERT_EQ(planner.plan().status, PlanStatus::kOk);
  planner.updateVoxel(VoxelIndex(7, 7, 0), Occupancy::kOccupied);
  EXPECT_EQ(planner.plan().status, PlanStatus::kGoalBlocked);
  planner.updateVoxel(VoxelIndex(7, 7, 0), Occupancy::kFree);
  const PlanResult r = planner.plan();
  EXPECT_EQ(r.status, PlanStatus::kOk);
  EXPECT_NEAR(r.cost, 7.0 * std::sqrt(2.0), 1e-9);
}

TEST(DStarLiteRegression, StartInsideAnObstacleIsAStatusNotAHang)
{
  DStarLite planner(box(6, 6, 1), {26, true, 0.0});
  planner.updateVoxel(VoxelIndex(0, 0, 0), Occupancy::kOccupied);
  planner.setStart(at(planner, 0, 0, 0));
  planner.setGoal(at(planner, 5, 5, 0));
  EXPECT_EQ(planner.plan().status, PlanStatus::kStartBlocked);
}

TEST(DStarLiteRegression, PathThroughUnknownLaterFoundOccupied)
{
  DStarLite planner(box(10, 10, 1), {6, true, 0.0});
  planner.setStart(at(planner, 0, 5, 0));
  planner.setGoal(at(planner, 9, 5, 0));
  PlanResult r = planner.plan();
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_NEAR(r.cost, 9.0, 1e-9);  // straight through unknown space
  for (int y = 2; y <= 8; ++y) {
    planner.updateVoxel(VoxelIndex(5, y, 0), Occupancy::kOccupied);
  }
  r = planner.plan();
  ASSERT_EQ(r.status, PlanStatus::kOk);
  EXPECT_NEAR(r.cost, shortestPathCost(planner, at(planner, 0, 5, 0), at(planner, 9, 5, 0)), 1e-9);
  EXPECT_GT(r.cost, 9.0);
  // Pessimistic about unknown space: nothing known, nothing traversable.
  DStarLite careful(box(10, 10, 1), {6, false, 0.0});
  careful.setStart(at(careful, 0, 5, 0));
  careful.setGoal(at(careful, 9, 5, 0));
  EXPECT_EQ(careful.plan().status, PlanStatus::kStartBlocked);
}

TEST(DStarLiteRegression, BudgetStopsAndTheNextCallContinues)
{
  DStarLite planner(box(30, 30, 1), {26, true, 0.0});
  planner.setStart(at(planner, 0, 0, 0));
  planner.setGoal(at(planner, 29, 29, 0));
  EXPECT_EQ(planner.plan(5).status, PlanStatus::kBudgetExceeded);
  const PlanResult r = planner.plan();
  EXPECT_EQ(r.status, PlanStatus::kOk);
  EXPECT_NEAR(r.cost, 29.0 * std::sqrt(2.0), 1e-9);
}

TEST(DStarLite, ADriftedStartEscapesToTheNearestFreeCell)
{
  DStarLite planner(box(10, 10, 1), {26, true, 1.2});
  planner.updateVoxel(VoxelIndex(5, 5, 0), Occupancy::kOccupied);
  const Cell inside = at(planner, 6, 5, 0);  // 0.5 m from the box: inside the margin
  ASSERT_FALSE(planner.traversable(inside));
  const auto out = planner.nearestTraversable(inside, 2.0);
  ASSERT_TRUE(out.has_value());
  EXPECT_TRUE(planner.traversable(*out));
  EXPECT_EQ(*out, at(planner, 7, 5, 0));  // one cell further away
  EXPECT_FALSE(planner.nearestTraversable(inside, 0.5).has_value());
}

TEST(DStarLite, SearchMemoryFollowsTheRegionSearchedNotTheBox)
{
  // 200 x 200 x 50 = 2,000,000 cells; a short search in one corner.
  DStarLite planner(box(200, 200, 50), {26, true, 0.0});
  planner.setGoal(at(planner, 10, 10, 2));
  planner.setStart(at(planner, 2, 2, 2));
  ASSERT_EQ(planner.plan().status, PlanStatus::kOk);
  const std::size_t whole_box = static_cast<std::size_t>(planner.lattice().size()) * 2 * sizeof(double);
  EXPECT_GT(planner.searchBytes(), 0U);
  EXPECT_LT(planner.searchBytes(), whole_box / 50) << "g and rhs for 2 % of the box at most";
}

TEST(DStarLite, CoordinatesAreTheLatticesOwnNumbering)
{
  // A box off the origin and with uneven sides; every cell's coordinates are its voxel less
  // the first voxel's, as the lattice numbers them.
  const Lattice lattice(VoxelGrid(0.5), Vector3(-3.2, 1.1, 0.4), Vector3(2.9, 4.0, 3.3));
  const DStarLite planner(lattice, {26, true, 0.0});
  const VoxelIndex first = lattice.voxel(0);
  for (Cell c = 0; c < lattice.size(); ++c) {
    ASSERT_EQ(planner.coordinates(c), lattice.voxel(c) - first) << "cell " << c;
  }
  // Sides of odd lengths and thirteen million cells: the divisions done as multiplications
  // hold far from the origin, to the last cell.
  const DStarLite large(box(1021, 997, 13), {26, true, 0.0});
  for (Cell c = 0; c < large.lattice().size(); c += 7919) {
    ASSERT_EQ(large.coordinates(c), large.lattice().voxel(c)) << "cell " << c;
  }
  const Cell last = large.lattice().size() - 1;
  EXPECT_EQ(large.coordinates(last), Eigen::Vector3i(1020, 996, 12));
}

TEST(DStarLite, BadConnectivityIsRefused)
{
  EXPECT_THROW(DStarLite(box(3, 3, 3), {8, true, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace quad::planning

#include "quad/planning/shortcut.hpp"

namespace quad::planning {
namespace {

TEST(Shortcut, StraightensThePathWithoutCuttingBlockedCells)
{
  DStarLite planner(box(20, 20, 1), {26, true, 0.0});
  for (int y = 0; y < 15; ++y) {
    planner.updateVoxel(VoxelIndex(10, y, 0), Occupancy::kOccupied);  // a wall with a gap at the top
  }
  planner.setStart(at(planner, 0, 0, 0));
  planner.setGoal(at(planner, 19, 0, 0));
  const PlanResult r = planner.plan();
  ASSERT_EQ(r.status, PlanStatus::kOk);
  const auto waypoints = shortcut(planner, r.cells);
  EXPECT_LT(waypoints.size(), r.cells.size());
  EXPECT_EQ(waypoints.front(), planner.lattice().centre(r.cells.front()));
  EXPECT_EQ(waypoints.back(), planner.lattice().centre(r.cells.back()));
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    EXPECT_TRUE(lineOfSight(planner, waypoints[i], waypoints[i + 1])) << i;
  }
  // Shortened, never longer than the lattice path.
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    length += (waypoints[i + 1] - waypoints[i]).norm();
  }
  EXPECT_LE(length, r.cost + 1e-9);
}

}  // namespace
}  // namespace quad::planning
