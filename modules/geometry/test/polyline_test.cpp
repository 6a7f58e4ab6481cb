// SPDX-License-Identifier: BSD-3-Clause
// Arc length along polylines: lengths, points, cuts and projections against hand-worked cases.
#include "quad/geometry/polyline.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace quad::geometry {
namespace {

// An L: 3 m along x, then 4 m up.
const std::vector<Vector3> kL{Vector3(0, 0, 0), Vector3(3, 0, 0), Vector3(3, 0, 4)};

TEST(Polyline, LengthIsTheSumOfItsSegments)
{
  EXPECT_DOUBLE_EQ(polylineLength(kL), 7.0);
  EXPECT_DOUBLE_EQ(polylineLength({Vector3(1, 2, 3)}), 0.0);
  EXPECT_DOUBLE_EQ(polylineLength({}), 0.0);
}

TEST(Polyline, PointAlongWalksTheSegmentsAndClampsAtTheEnds)
{
  EXPECT_TRUE(pointAlong(kL, 1.5).isApprox(Vector3(1.5, 0, 0)));
  EXPECT_TRUE(pointAlong(kL, 5.0).isApprox(Vector3(3, 0, 2)));
  EXPECT_TRUE(pointAlong(kL, -1.0).isApprox(kL.front()));
  EXPECT_TRUE(pointAlong(kL, 99.0).isApprox(kL.back()));
  EXPECT_THROW(pointAlong({}, 1.0), std::invalid_argument);
}

TEST(Polyline, TruncatedKeepsThePointsBeforeTheCutAndEndsOnIt)
{
  const auto cut = truncated(kL, 5.0);
  ASSERT_EQ(cut.size(), 3U);
  EXPECT_TRUE(cut[2].isApprox(Vector3(3, 0, 2)));
  EXPECT_NEAR(polylineLength(cut), 5.0, 1e-12);
  EXPECT_EQ(truncated(kL, 0.0).size(), 1U);  // the first point alone
  EXPECT_EQ(truncated(kL, 100.0), kL);       // past the end: all of it
}

TEST(Polyline, NearestArcLengthProjectsOntoTheClosestSegment)
{
  EXPECT_NEAR(nearestArcLength(kL, Vector3(1, 2, 0)), 1.0, 1e-12);
  EXPECT_NEAR(nearestArcLength(kL, Vector3(5, 0, 3)), 6.0, 1e-12);
  EXPECT_NEAR(nearestArcLength(kL, Vector3(-4, 0, 0)), 0.0, 1e-12);
}

TEST(Polyline, DistanceToPolylineIsToTheNearestSegmentOrEnd)
{
  EXPECT_NEAR(distanceToPolyline(kL, Vector3(1, 2, 0)), 2.0, 1e-12);   // beside the first segment
  EXPECT_NEAR(distanceToPolyline(kL, Vector3(-3, -4, 0)), 5.0, 1e-12);  // past its first end
  EXPECT_NEAR(distanceToPolyline(kL, Vector3(4, 0, 3)), 1.0, 1e-12);   // beside the second
  EXPECT_NEAR(distanceToPolyline({Vector3(1, 1, 1)}, Vector3(1, 1, 3)), 2.0, 1e-12);
  EXPECT_TRUE(std::isinf(distanceToPolyline({}, Vector3::Zero())));
}

}  // namespace
}  // namespace quad::geometry
