// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/distance.hpp"

#include <algorithm>
#include <cmath>

namespace quad::geometry {

double rhoS(const Quaternion& h1, const Quaternion& h2)
{
  // Rounding can put the dot product of unit quaternions just outside [−1, 1].
  return std::acos(std::clamp(dot(h1.normalized(), h2.normalized()), -1.0, 1.0));
}

double rho(const Quaternion& h1, const Quaternion& h2) { return std::min(rhoS(h1, h2), rhoS(h1, -h2)); }

double yprDistance(const YawPitchRoll& a, const YawPitchRoll& b)
{
  const double dy = wrapToPi(a.yaw - b.yaw);
  const double dp = wrapToPi(a.pitch - b.pitch);
  const double dr = wrapToPi(a.roll - b.roll);
  return std::sqrt(dy * dy + dp * dp + dr * dr);
}

double frobeniusDistance(const Matrix3& R1, const Matrix3& R2) { return (R1 - R2).norm(); }

double geodesicAngle(const Quaternion& q1, const Quaternion& q2)
{
  // Angle of q1* ⊗ q2 = 2 atan2(|v|, |w|): no acos, so no lost digits near 0 or π.
  const Quaternion r = q1.normalized().conjugate() * q2.normalized();
  return 2.0 * std::atan2(r.imaginary().norm(), std::abs(r.w));
}

double geodesicAngle(const Matrix3& R1, const Matrix3& R2)
{
  return axisAngleFromMatrix(R1.transpose() * R2).angle;
}

}  // namespace quad::geometry
