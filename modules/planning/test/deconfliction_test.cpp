// SPDX-License-Identifier: BSD-3-Clause
// Deconfliction by priority: the tubes kept out of, against the closed-form distance to a
// segment, and whose paths make them.
#include "quad/planning/deconfliction.hpp"

#include <gtest/gtest.h>

#include <random>

#include "quad/geometry/polyline.hpp"

namespace quad::planning {
namespace {

using geometry::VoxelGrid;

/// 20 × 10 × 6 m at 0.2 m.
Lattice field() { return Lattice(VoxelGrid(0.2), Vector3(0, 0, 0), Vector3(20, 10, 6)); }

/// [m] From p to the polyline's segments (its only point when it has one).
double polylineDistance(const Vector3& p, const std::vector<Vector3>& line)
{
  double best = (p - line.front()).norm();
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Vector3 ab = line[k] - line[k - 1];
    const double s = std::clamp((p - line[k - 1]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (line[k - 1] + s * ab)).norm());
  }
  return best;
}

TEST(CellsNear, ExactlyTheCellsWithinTheClearanceOfTheLookaheadAreKeptOut)
{
  const Lattice lattice = field();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(1.0, 19.0), y(1.0, 9.0), z(1.0, 5.0);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<Vector3> path{{x(rng), y(rng), z(rng)}, {x(rng), y(rng), z(rng)}, {x(rng), y(rng), z(rng)}};
    const double lookahead = 3.0 + 0.25 * trial;
    const double clearance = 0.5 + 0.07 * trial;
    const std::vector<Cell> cells = cellsNear(lattice, path, lookahead, clearance);
    ASSERT_TRUE(std::is_sorted(cells.begin(), cells.end()));
    const std::vector<Vector3> ahead = geometry::truncated(path, lookahead);
    std::size_t expected = 0;
    for (Cell c = 0; c < lattice.size(); ++c) {
      const bool near = polylineDistance(lattice.centre(c), ahead) <= clearance;
      expected += near ? 1U : 0U;
      EXPECT_EQ(std::binary_search(cells.begin(), cells.end(), c), near) << "trial " << trial << " cell " << c;
    }
    EXPECT_EQ(cells.size(), expected);
    EXPECT_GT(expected, 0U);
  }
  // A path of one point: a ball; an empty one: nothing.
  const auto ball = cellsNear(lattice, {{10, 5, 3}}, 4.0, 1.0);
  for (const Cell c : ball) {
    EXPECT_LE((lattice.centre(c) - Vector3(10, 5, 3)).norm(), 1.0);
  }
  EXPECT_NEAR(static_cast<double>(ball.size()), 4.0 / 3.0 * 3.14159265 / 0.008, 40.0);
  EXPECT_TRUE(cellsNear(lattice, {}, 4.0, 1.0).empty());
}

TEST(Deconfliction, TheHigherIdYieldsToTheLowerWhilePathsAreFresh)
{
  const Lattice lattice = field();
  const std::int64_t s = 1'000'000'000;
  Deconfliction two(2, {1.0, 4.0, 2.0}, 0.65, 0.35);
  EXPECT_DOUBLE_EQ(two.clearance(), 2.0);
  const std::vector<Vector3> first{{2, 5, 2}, {18, 5, 2}};
  two.onPath(1, 1 * s, first);
  two.onPath(3, 1 * s, {{2, 2, 2}, {18, 2, 2}});  // vehicle 3 yields to 2, not 2 to it
  two.onPath(2, 1 * s, {{2, 8, 2}, {18, 8, 2}});  // its own
  // In effect kPathEffectDelayNs after its stamp, not before.
  EXPECT_TRUE(two.yieldingTo(1 * s + kPathEffectDelayNs - 1).empty());
  EXPECT_EQ(two.yieldingTo(1 * s + kPathEffectDelayNs), std::vector<std::uint32_t>{1});
  EXPECT_EQ(two.keepOut(lattice, 2 * s), cellsNear(lattice, first, 4.0, 2.0));
  // A newer path replaces it once in effect; one not newer than the newest heard is ignored.
  const std::vector<Vector3> second{{10, 1, 1}};
  two.onPath(1, 2 * s, second);
  two.onPath(1, 2 * s, first);
  EXPECT_EQ(two.keepOut(lattice, 2 * s + kPathEffectDelayNs - 1), cellsNear(lattice, first, 4.0, 2.0));
  EXPECT_EQ(two.keepOut(lattice, 2 * s + kPathEffectDelayNs), cellsNear(lattice, second, 4.0, 2.0));
  // Stale after the timeout; a path without points (no path) is none to keep out of.
  EXPECT_EQ(two.yieldingTo(4 * s).size(), 1U);
  EXPECT_TRUE(two.yieldingTo(4 * s + 1).empty());
  EXPECT_TRUE(two.keepOut(lattice, 4 * s + 1).empty());
  two.onPath(1, 5 * s, {});
  EXPECT_TRUE(two.yieldingTo(5 * s + kPathEffectDelayNs).empty());
  // Vehicle 1 yields to no one.
  Deconfliction one(1, {}, 0.65, 0.35);
  one.onPath(2, s, {{2, 8, 2}});
  EXPECT_TRUE(one.yieldingTo(2 * s).empty());
  EXPECT_FALSE(yieldsTo(1, 2));
  EXPECT_TRUE(yieldsTo(2, 1));
}

}  // namespace
}  // namespace quad::planning
