// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/polyline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace quad::geometry {

namespace {
/// The parameter u in [0, 1] of the point of segment a → b nearest to p.
double nearestOnSegment(const Vector3& a, const Vector3& b, const Vector3& p)
{
  const Vector3 segment = b - a;
  const double length2 = segment.squaredNorm();
  return length2 > 0.0 ? std::clamp((p - a).dot(segment) / length2, 0.0, 1.0) : 0.0;
}
}  // namespace

double polylineLength(const std::vector<Vector3>& points)
{
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    length += (points[i] - points[i - 1]).norm();
  }
  return length;
}

Vector3 pointAlong(const std::vector<Vector3>& points, double s)
{
  if (points.empty()) {
    throw std::invalid_argument("pointAlong: an empty polyline has no points");
  }
  double walked = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double segment = (points[i] - points[i - 1]).norm();
    if (walked + segment >= s && segment > 0.0) {
      const double u = std::clamp((s - walked) / segment, 0.0, 1.0);
      return points[i - 1] + u * (points[i] - points[i - 1]);
    }
    walked += segment;
  }
  return s <= 0.0 ? points.front() : points.back();
}

std::vector<Vector3> truncated(const std::vector<Vector3>& points, double s)
{
  std::vector<Vector3> out;
  if (points.empty()) {
    return out;
  }
  out.push_back(points.front());
  double walked = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double segment = (points[i] - points[i - 1]).norm();
    if (walked + segment >= s) {
      const double u = segment > 0.0 ? std::clamp((s - walked) / segment, 0.0, 1.0) : 0.0;
      if (u > 0.0) {
        out.push_back(points[i - 1] + u * (points[i] - points[i - 1]));
      }
      return out;
    }
    out.push_back(points[i]);
    walked += segment;
  }
  return out;
}

double nearestArcLength(const std::vector<Vector3>& points, const Vector3& p)
{
  double best = std::numeric_limits<double>::infinity();
  double best_s = 0.0;
  double walked = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Vector3 segment = points[i] - points[i - 1];
    const double u = nearestOnSegment(points[i - 1], points[i], p);
    const double d = (points[i - 1] + u * segment - p).norm();
    const double length = segment.norm();
    if (d < best) {
      best = d;
      best_s = walked + u * length;
    }
    walked += length;
  }
  return best_s;
}

double distanceToPolyline(const std::vector<Vector3>& points, const Vector3& p)
{
  if (points.size() == 1) {
    return (points.front() - p).norm();
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double u = nearestOnSegment(points[i - 1], points[i], p);
    best = std::min(best, (points[i - 1] + u * (points[i] - points[i - 1]) - p).norm());
  }
  return best;
}

}  // namespace quad::geometry
