// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Hamilton quaternions, stored scalar first: (w, x, y, z) = w + x i + y j + z k, with
/// i² = j² = k² = ijk = −1 (the guide's Table 1). A unit quaternion q rotates v by
/// q ⊗ (0, v) ⊗ q*; q and −q are the same rotation (unit quaternions cover SO(3) twice).
///
/// The guide writes quaternions scalar first, (a, b, c, d), except in its eq. (4), which is
/// scalar last; quad is scalar first everywhere: here, in IDL (Quaternion.idl) and on the
/// command line.

#include <Eigen/Core>

#include "quad/geometry/so3.hpp"

namespace quad::geometry {

struct Quaternion {
  double w = 1.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  static Quaternion identity() { return {}; }
  /// From (w, x, y, z) in that order.
  static Quaternion fromVector(const Eigen::Vector4d& wxyz) { return {wxyz[0], wxyz[1], wxyz[2], wxyz[3]}; }
  Eigen::Vector4d vector() const { return {w, x, y, z}; }
  Vector3 imaginary() const { return {x, y, z}; }

  double norm() const;
  /// Throws std::invalid_argument on a zero or non-finite quaternion.
  Quaternion normalized() const;
  Quaternion conjugate() const { return {w, -x, -y, -z}; }
  /// q⁻¹ = q* / |q|²; throws std::invalid_argument on zero.
  Quaternion inverse() const;
  Quaternion operator-() const { return {-w, -x, -y, -z}; }
  /// The representative with w > 0 (or, when w = 0, the first non-zero of x, y, z positive).
  Quaternion canonical() const;
};

/// Hamilton product p ⊗ q.
Quaternion operator*(const Quaternion& p, const Quaternion& q);

double dot(const Quaternion& p, const Quaternion& q);

/// L(q) p = q ⊗ p and R(q) p = p ⊗ q, on (w, x, y, z) column vectors; so q ⊗ p = L(q) p = R(p) q.
Eigen::Matrix4d leftMatrix(const Quaternion& q);
Eigen::Matrix4d rightMatrix(const Quaternion& q);

/// Rotates v by the unit quaternion q.
Vector3 rotate(const Quaternion& q, const Vector3& v);

/// The rotation matrix of a unit quaternion (q is normalized first).
Matrix3 toMatrix(const Quaternion& q);

/// Shepperd's method (1978): pivots on the largest of w², x², y², z², so it is accurate for
/// every angle including 180°. Returns the canonical representative. The input is projected
/// onto SO(3) only by the arithmetic's own rounding: check isRotation first for outside input.
Quaternion fromMatrix(const Matrix3& R);

/// cos(θ/2) + sin(θ/2) n, with `axis` normalized; throws on a zero axis.
Quaternion fromAxisAngle(const Vector3& axis, double angle);

/// Spherical linear interpolation along the shorter arc, t in [0, 1]; falls back to
/// normalized linear interpolation when the quaternions are nearly parallel.
Quaternion slerp(const Quaternion& a, const Quaternion& b, double t);

}  // namespace quad::geometry
