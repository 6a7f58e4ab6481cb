// SPDX-License-Identifier: BSD-3-Clause
// The minimum-snap spline: its closed form from rest to rest, its constraints, its continuity,
// and its optimality against every other spline through the same points.
#include "quad/trajectory/min_snap.hpp"

#include <gtest/gtest.h>

#include <random>

namespace quad::trajectory {
namespace {

State at(const Vector3& p) { return State{p, Vector3::Zero(), Vector3::Zero(), Vector3::Zero()}; }

TEST(MinimumSnap, FromRestToRestInOnePieceIsTheClosedFormSeptic)
{
  // GIVEN one piece from rest at a to rest at b
  const Vector3 a(1, -2, 3);
  const Vector3 b(4, 2, 3);
  // WHEN solved
  const auto pieces = minimumSnap(at(a), {}, at(b), {2.5});
  ASSERT_TRUE(pieces);
  // THEN it is a + (b − a)(35τ⁴ − 84τ⁵ + 70τ⁶ − 20τ⁷), whatever the duration
  const Coefficients& c = pieces->front().c;
  EXPECT_TRUE(c.col(0).isApprox(a));
  for (int k = 1; k < 4; ++k) {
    EXPECT_LT(c.col(k).norm(), 1e-9);
  }
  const double expected[] = {35, -84, 70, -20};
  for (int k = 4; k < 8; ++k) {
    EXPECT_LT((c.col(k) - expected[k - 4] * (b - a)).norm(), 1e-8) << k;
  }
  // ... whose peak speed is 35/16 of the mean
  EXPECT_NEAR(pieces->front().at(1.25).v.norm(), 35.0 / 16.0 * 5.0 / 2.5, 1e-9);
}

/// A spline through random points with random start and end states.
struct Case {
  State start;
  State end;
  std::vector<Vector3> through;
  std::vector<double> durations;
};

Case randomCase(std::mt19937& rng, int pieces)
{
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  std::uniform_real_distribution<double> duration(0.2, 3.0);
  const auto vector = [&] { return Vector3(coordinate(rng), coordinate(rng), coordinate(rng)); };
  Case c;
  c.start = State{vector(), 0.5 * vector(), 0.5 * vector(), vector()};
  c.end = State{vector(), 0.2 * vector(), Vector3::Zero(), Vector3::Zero()};
  for (int i = 0; i + 1 < pieces; ++i) {
    c.through.push_back(vector());
  }
  for (int i = 0; i < pieces; ++i) {
    c.durations.push_back(duration(rng));
  }
  return c;
}

TEST(MinimumSnap, MeetsItsEndsPassesItsPointsOnTimeAndIsSmoothThroughThem)
{
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Case c = randomCase(rng, 1 + trial % 7);
    const auto pieces = minimumSnap(c.start, c.through, c.end, c.durations);
    ASSERT_TRUE(pieces);
    const State s = pieces->front().at(0.0);
    EXPECT_LT((s.p - c.start.p).norm() + (s.v - c.start.v).norm() + (s.a - c.start.a).norm() +
                  (s.j - c.start.j).norm(), 1e-7);
    const State e = pieces->back().at(pieces->back().duration);
    EXPECT_LT((e.p - c.end.p).norm() + (e.v - c.end.v).norm() + (e.a - c.end.a).norm() + (e.j - c.end.j).norm(),
              1e-7);
    for (std::size_t i = 1; i < pieces->size(); ++i) {
      const Piece& before = (*pieces)[i - 1];
      const Piece& after = (*pieces)[i];
      const State b = before.at(before.duration);
      const State a = after.at(0.0);
      EXPECT_LT((b.p - c.through[i - 1]).norm(), 1e-8);
      EXPECT_LT((a.p - c.through[i - 1]).norm(), 1e-8);
      const double scale = 1.0 + b.j.norm();
      EXPECT_LT((b.v - a.v).norm(), 1e-7 * scale);
      EXPECT_LT((b.a - a.a).norm(), 1e-7 * scale);
      EXPECT_LT((b.j - a.j).norm(), 1e-7 * scale);
      EXPECT_LT((before.snap(before.duration) - after.snap(0.0)).norm(), 1e-6 * (1.0 + after.snap(0.0).norm()));
    }
  }
}

TEST(MinimumSnap, NoOtherSplineThroughThePointsHasLessSnap)
{
  // GIVEN the minimum-snap spline through random points, and others through the same points
  // at the same times: each interior point's velocity, acceleration and jerk perturbed, each
  // piece then the one septic with those ends (a piece solved alone from state to state)
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const Case c = randomCase(rng, 2 + trial % 4);
    const auto best = minimumSnap(c.start, c.through, c.end, c.durations);
    ASSERT_TRUE(best);
    const double optimum = snapCost(*best);
    for (int variant = 0; variant < 10; ++variant) {
      const double size = variant == 0 ? 0.0 : 0.05 * variant;
      std::vector<State> knots{c.start};
      for (std::size_t i = 1; i < best->size(); ++i) {
        State k = (*best)[i].at(0.0);
        k.v += size * Vector3(noise(rng), noise(rng), noise(rng));
        k.a += size * Vector3(noise(rng), noise(rng), noise(rng));
        k.j += size * Vector3(noise(rng), noise(rng), noise(rng));
        knots.push_back(k);
      }
      knots.push_back(c.end);
      std::vector<Piece> other;
      for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
        const auto piece = minimumSnap(knots[i], {}, knots[i + 1], {c.durations[i]});
        ASSERT_TRUE(piece);
        other.push_back(piece->front());
      }
      // THEN none has less snap, and the unperturbed one is the same spline
      if (variant == 0) {
        EXPECT_NEAR(snapCost(other), optimum, 1e-6 * optimum);
      } else {
        EXPECT_GT(snapCost(other), optimum * (1.0 - 1e-9)) << "trial " << trial << " variant " << variant;
      }
    }
  }
}

TEST(MinimumSnap, RefusesSizesThatDisagreeAndValuesThatAreNotFinite)
{
  const State s = at(Vector3::Zero());
  EXPECT_FALSE(minimumSnap(s, {}, s, {}));
  EXPECT_FALSE(minimumSnap(s, {Vector3::Ones()}, s, {1.0}));
  EXPECT_FALSE(minimumSnap(s, {}, s, {0.0}));
  EXPECT_FALSE(minimumSnap(s, {Vector3(std::nan(""), 0, 0)}, s, {1.0, 1.0}));
  State bad = s;
  bad.j.x() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(minimumSnap(bad, {}, s, {1.0}));
  EXPECT_TRUE(minimumSnap(s, {Vector3::Ones()}, s, {1.0, 1e-3}));  // unequal pieces solve too
}

}  // namespace
}  // namespace quad::trajectory
