// SPDX-License-Identifier: BSD-3-Clause
// The curve along a path: within the corner deviation of its corners, tangent and smooth,
// exact on straight stretches.
#include "quad/trajectory/curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quad/geometry/polyline.hpp"

namespace quad::trajectory {
namespace {

TEST(Curve, AStraightPathIsItselfWithoutCurvature)
{
  const Curve c({Vector3(0, 0, 1), Vector3(3, 4, 1)}, 0.1, 0.05);
  EXPECT_NEAR(c.length(), 5.0, 1e-12);
  EXPECT_TRUE(c.at(2.5).p.isApprox(Vector3(1.5, 2.0, 1.0)));
  EXPECT_TRUE(c.at(2.5).tangent.isApprox(Vector3(0.6, 0.8, 0.0)));
  EXPECT_EQ(c.at(2.5).curvature, 0.0);
  EXPECT_TRUE(c.at(-1.0).p.isApprox(Vector3(0, 0, 1)));  // clamped at both ends
  EXPECT_TRUE(c.at(9.0).p.isApprox(Vector3(3, 4, 1)));
}

TEST(Curve, CornersAreRoundedWithinTheDeviationAndTheTangentTurnsSmoothly)
{
  // GIVEN random polylines turning by up to 120° at each corner, and corner deviations
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> length(0.5, 8.0);
  std::uniform_real_distribution<double> deflection(-2.0 * std::acos(-1.0) / 3.0, 2.0 * std::acos(-1.0) / 3.0);
  std::uniform_real_distribution<double> deviation(0.05, 0.4);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Vector3> path{Vector3(0, 0, 2)};
    double heading = 0.0;
    for (int i = 0; i < 5; ++i) {
      heading += deflection(rng);
      path.push_back(path.back() + length(rng) * Vector3(std::cos(heading), std::sin(heading), 0.0));
    }
    const double d = deviation(rng);
    const Curve c(path, d, 0.02);
    // THEN every sample is within the deviation of the polyline, starts and ends on it, and
    // the tangent turns by no more than the spacing's worth of curvature between samples
    for (std::size_t i = 0; i < c.samples().size(); ++i) {
      EXPECT_LE(geometry::distanceToPolyline(path, c.samples()[i].p), d * 1.001) << trial;
      if (i > 0) {
        const double step = c.arcLengths()[i] - c.arcLengths()[i - 1];
        const double turn = std::acos(std::clamp(c.samples()[i].tangent.dot(c.samples()[i - 1].tangent), -1.0, 1.0));
        EXPECT_LE(turn, std::max(c.samples()[i].curvature, c.samples()[i - 1].curvature) * step * 1.5 + 1e-6);
      }
    }
    EXPECT_TRUE(c.at(0.0).p.isApprox(path.front()));
    EXPECT_TRUE(c.at(c.length()).p.isApprox(path.back()));
    EXPECT_LE(c.length(), geometry::polylineLength(path) + 1e-9);  // rounding cuts corners
  }
}

TEST(Curve, RefusesNoPointsAndNonFiniteOnes)
{
  EXPECT_THROW(Curve({}, 0.1, 0.05), std::invalid_argument);
  EXPECT_THROW(Curve({Vector3(0, 0, std::nan(""))}, 0.1, 0.05), std::invalid_argument);
  EXPECT_THROW(Curve({Vector3::Zero()}, 0.0, 0.05), std::invalid_argument);
  const Curve single({Vector3(1, 1, 1)}, 0.1, 0.05);
  EXPECT_EQ(single.length(), 0.0);
}

}  // namespace
}  // namespace quad::trajectory
