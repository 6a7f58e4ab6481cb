// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/quaternion.hpp"

#include <cmath>
#include <stdexcept>

namespace quad::geometry {

double Quaternion::norm() const { return std::sqrt(w * w + x * x + y * y + z * z); }

Quaternion Quaternion::normalized() const
{
  const double n = norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw std::invalid_argument("quaternion: cannot normalize a zero or non-finite quaternion");
  }
  return {w / n, x / n, y / n, z / n};
}

Quaternion Quaternion::inverse() const
{
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > 0.0) || !std::isfinite(n2)) {
    throw std::invalid_argument("quaternion: a zero or non-finite quaternion has no inverse");
  }
  return {w / n2, -x / n2, -y / n2, -z / n2};
}

Quaternion Quaternion::canonical() const
{
  for (const double c : {w, x, y, z}) {
    if (c != 0.0) {
      return c > 0.0 ? *this : -*this;
    }
  }
  return *this;
}

Quaternion operator*(const Quaternion& p, const Quaternion& q)
{
  return {p.w * q.w - p.x * q.x - p.y * q.y - p.z * q.z,
          p.w * q.x + p.x * q.w + p.y * q.z - p.z * q.y,
          p.w * q.y - p.x * q.z + p.y * q.w + p.z * q.x,
          p.w * q.z + p.x * q.y - p.y * q.x + p.z * q.w};
}

double dot(const Quaternion& p, const Quaternion& q)
{
  return p.w * q.w + p.x * q.x + p.y * q.y + p.z * q.z;
}

Eigen::Matrix4d leftMatrix(const Quaternion& q)
{
  Eigen::Matrix4d L;
  L << q.w, -q.x, -q.y, -q.z,
       q.x,  q.w, -q.z,  q.y,
       q.y,  q.z,  q.w, -q.x,
       q.z, -q.y,  q.x,  q.w;
  return L;
}

Eigen::Matrix4d rightMatrix(const Quaternion& q)
{
  Eigen::Matrix4d R;
  R << q.w, -q.x, -q.y, -q.z,
       q.x,  q.w,  q.z, -q.y,
       q.y, -q.z,  q.w,  q.x,
       q.z,  q.y, -q.x,  q.w;
  return R;
}

Vector3 rotate(const Quaternion& q, const Vector3& v) { return toMatrix(q) * v; }

Matrix3 toMatrix(const Quaternion& q_in)
{
  const Quaternion q = q_in.normalized();
  const double ww = q.w * q.w, xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  Matrix3 R;
  R << ww + xx - yy - zz, 2 * (xy - wz), 2 * (xz + wy),
       2 * (xy + wz), ww - xx + yy - zz, 2 * (yz - wx),
       2 * (xz - wy), 2 * (yz + wx), ww - xx - yy + zz;
  return R;
}

Quaternion fromMatrix(const Matrix3& R)
{
  // 4w² = 1 + tr R, 4x² = 1 + R00 − R11 − R22, ...: divide by the largest for accuracy.
  const double tr = R.trace();
  Quaternion q;
  if (tr >= R(0, 0) && tr >= R(1, 1) && tr >= R(2, 2)) {
    const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 + tr));  // 4w
    q = {0.25 * s, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s};
  } else if (R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2)) {
    const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 + R(0, 0) - R(1, 1) - R(2, 2)));  // 4x
    q = {(R(2, 1) - R(1, 2)) / s, 0.25 * s, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s};
  } else if (R(1, 1) >= R(2, 2)) {
    const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 - R(0, 0) + R(1, 1) - R(2, 2)));  // 4y
    q = {(R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, 0.25 * s, (R(1, 2) + R(2, 1)) / s};
  } else {
    const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 - R(0, 0) - R(1, 1) + R(2, 2)));  // 4z
    q = {(R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, 0.25 * s};
  }
  return q.normalized().canonical();
}

Quaternion fromAxisAngle(const Vector3& axis, double angle)
{
  const double n = axis.norm();
  if (!(n > 0.0) || !std::isfinite(n) || !std::isfinite(angle)) {
    throw std::invalid_argument("fromAxisAngle: axis must be non-zero and finite, angle finite");
  }
  const Vector3 v = axis / n * std::sin(angle / 2.0);
  return {std::cos(angle / 2.0), v.x(), v.y(), v.z()};
}

Quaternion slerp(const Quaternion& a_in, const Quaternion& b_in, double t)
{
  const Quaternion a = a_in.normalized();
  Quaternion b = b_in.normalized();
  double d = dot(a, b);
  if (d < 0.0) {  // the shorter arc: b and −b are the same rotation
    b = -b;
    d = -d;
  }
  if (d > 1.0 - 1e-12) {
    // Nearly parallel: sin θ ≈ 0; normalized lerp is exact to rounding here.
    return Quaternion{a.w + t * (b.w - a.w), a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
                      a.z + t * (b.z - a.z)}
        .normalized();
  }
  const double theta = std::acos(d);
  const double s = std::sin(theta);
  const double ka = std::sin((1.0 - t) * theta) / s;
  const double kb = std::sin(t * theta) / s;
  return {ka * a.w + kb * b.w, ka * a.x + kb * b.x, ka * a.y + kb * b.y, ka * a.z + kb * b.z};
}

}  // namespace quad::geometry
