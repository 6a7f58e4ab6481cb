// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Arc length along a polyline of points [m]: what a planned path is between the planner
/// that makes it and the follower that flies it.

#include <vector>

#include "quad/geometry/so3.hpp"

namespace quad::geometry {

/// The sum of the segments' lengths; 0 for fewer than two points.
double polylineLength(const std::vector<Vector3>& points);

/// The point at arc length s from the first point, s clamped to [0, length]. Throws
/// std::invalid_argument on an empty polyline.
Vector3 pointAlong(const std::vector<Vector3>& points, double s);

/// The polyline from its first point up to arc length s (s clamped to [0, length]): the
/// points before s, then the point at s. An empty polyline stays empty.
std::vector<Vector3> truncated(const std::vector<Vector3>& points, double s);

/// The arc length of the point of the polyline nearest to p (the first such, on ties); 0 for
/// fewer than two points.
double nearestArcLength(const std::vector<Vector3>& points, const Vector3& p);

/// The distance [m] from p to the nearest point of the polyline (to its one point when it has
/// one); infinite for an empty polyline.
double distanceToPolyline(const std::vector<Vector3>& points, const Vector3& p);

}  // namespace quad::geometry
