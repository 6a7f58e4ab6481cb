// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/cspace.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace quad::geometry {

std::size_t cspaceDimension(int n)
{
  if (n < 1) {
    throw std::invalid_argument("cspaceDimension: n = " + std::to_string(n) + ", expected n >= 1");
  }
  const auto un = static_cast<std::size_t>(n);
  return un * (un + 1) / 2;
}

CarConfiguration::CarConfiguration(double x, double y, double theta)
    : x_(x), y_(y), theta_(wrapToTwoPi(theta))
{
}

double carDistance(const CarConfiguration& a, const CarConfiguration& b, double length)
{
  const double dx = a.x() - b.x();
  const double dy = a.y() - b.y();
  const double dtheta = length * wrapToPi(a.theta() - b.theta());
  return std::sqrt(dx * dx + dy * dy + dtheta * dtheta);
}

Pose3 Pose3::operator*(const Pose3& other) const
{
  return {p + rotate(q, other.p), (q * other.q).normalized()};
}

Pose3 Pose3::inverse() const
{
  const Quaternion qi = q.conjugate();
  return {-rotate(qi, p), qi};
}

Vector3 Pose3::transform(const Vector3& point_B) const { return p + rotate(q, point_B); }

}  // namespace quad::geometry
