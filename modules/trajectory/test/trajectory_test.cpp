// SPDX-License-Identifier: BSD-3-Clause
// Pieces and trajectories: derivatives against finite differences, the ends, refused input.
#include "quad/trajectory/trajectory.hpp"

#include <gtest/gtest.h>

#include <random>

namespace quad::trajectory {
namespace {

Piece randomPiece(std::mt19937& rng, double duration)
{
  std::uniform_real_distribution<double> coefficient(-3.0, 3.0);
  Piece p;
  p.duration = duration;
  for (int axis = 0; axis < 3; ++axis) {
    for (int k = 0; k < kCoefficients; ++k) {
      p.c(axis, k) = coefficient(rng);
    }
  }
  return p;
}

TEST(Piece, EachDerivativeIsTheRateOfChangeOfTheOneBefore)
{
  // GIVEN random pieces of several durations
  std::mt19937 rng(3);
  for (const double duration : {0.05, 0.7, 4.0}) {
    const Piece piece = randomPiece(rng, duration);
    const double h = 1e-6 * duration;
    for (const double u : {0.1, 0.5, 0.9}) {
      const double t = u * duration;
      // WHEN differentiated numerically  THEN each derivative matches the next one returned
      const State before = piece.at(t - h);
      const State after = piece.at(t + h);
      const State s = piece.at(t);
      const double scale = 1.0 / duration;
      EXPECT_LT(((after.p - before.p) / (2 * h) - s.v).norm(), 1e-5 * (1.0 + s.v.norm())) << duration;
      EXPECT_LT(((after.v - before.v) / (2 * h) - s.a).norm(), 1e-5 * (1.0 + s.a.norm()) * scale) << duration;
      EXPECT_LT(((after.a - before.a) / (2 * h) - s.j).norm(), 1e-5 * (1.0 + s.j.norm()) * scale) << duration;
      EXPECT_LT(((after.j - before.j) / (2 * h) - piece.snap(t)).norm(), 1e-5 * (1.0 + piece.snap(t).norm()) * scale)
          << duration;
    }
  }
}

TEST(Trajectory, BeforeItsStartItIsItsStartAndAfterItsEndAtRestAtItsEnd)
{
  std::mt19937 rng(5);
  const Trajectory t(10.0, {randomPiece(rng, 1.0), randomPiece(rng, 2.0)});
  EXPECT_DOUBLE_EQ(t.endTime(), 13.0);
  EXPECT_TRUE(t.at(9.0).p.isApprox(t.pieces().front().at(0.0).p));
  EXPECT_TRUE(t.at(9.0).v.isApprox(t.pieces().front().at(0.0).v));
  const State end = t.at(20.0);
  EXPECT_TRUE(end.p.isApprox(t.pieces().back().at(2.0).p));
  EXPECT_EQ(end.v, Vector3::Zero());
  EXPECT_EQ(end.a, Vector3::Zero());
  // Within: the piece that holds the time, from its own start.
  EXPECT_TRUE(t.at(11.5).p.isApprox(t.pieces()[1].at(0.5).p));
}

TEST(Trajectory, LengthOfAStraightLineAtConstantSpeedIsSpeedTimesTime)
{
  Piece p;
  p.duration = 2.0;
  p.c.col(1) = Vector3(6.0, 8.0, 0.0);  // 10 m over the piece: 5 m/s
  const Trajectory t(0.0, {p});
  EXPECT_NEAR(t.length(0.0, 2.0), 10.0, 1e-9);
  EXPECT_NEAR(t.length(0.5, 1.0), 2.5, 1e-9);
  EXPECT_NEAR(t.length(-5.0, 50.0), 10.0, 1e-9);  // clipped to the trajectory
}

TEST(Trajectory, RefusesNoPieceANonPositiveDurationAndNonFiniteValues)
{
  EXPECT_THROW(Trajectory(0.0, {}), std::invalid_argument);
  Piece p;
  p.duration = 0.0;
  EXPECT_THROW(Trajectory(0.0, {p}), std::invalid_argument);
  p.duration = 1.0;
  p.c(1, 3) = std::nan("");
  EXPECT_THROW(Trajectory(0.0, {p}), std::invalid_argument);
  p.c(1, 3) = 0.0;
  EXPECT_THROW(Trajectory(std::nan(""), {p}), std::invalid_argument);
  EXPECT_NO_THROW(Trajectory(0.0, {p}));
}

TEST(Trajectory, RestingStaysPut)
{
  const Trajectory t = restingAt(Vector3(1, 2, 3), 4.0, 2.0);
  for (const double time : {0.0, 4.0, 5.0, 9.0}) {
    EXPECT_EQ(t.at(time).p, Vector3(1, 2, 3));
    EXPECT_EQ(t.at(time).v, Vector3::Zero());
  }
}

}  // namespace
}  // namespace quad::trajectory
