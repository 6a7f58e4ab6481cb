// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Rotation matrices: SO(n) membership, projection onto SO(3), elementary rotations,
/// axis–angle, the exponential and logarithm maps, and yaw–pitch–roll angles.
///
/// Conventions: right-handed frames; a positive angle turns counter-clockwise when seen from
/// the tip of the axis; R_AB maps vectors in frame B to frame A.

#include <Eigen/Core>

namespace quad::geometry {

using Matrix3 = Eigen::Matrix3d;
using Vector3 = Eigen::Vector3d;

inline constexpr double kPi = 3.141592653589793238462643383279502884;

/// True if A is square with AᵀA = I and det A = 1, each within `tolerance` (max-abs entry
/// error of AᵀA − I, and |det A − 1|). Works for any n: SO(n).
bool isRotation(const Eigen::MatrixXd& A, double tolerance = 1e-9);

/// The rotation nearest to A in the Frobenius norm (polar decomposition via SVD, with the
/// sign of the smallest singular direction flipped when det < 0). Throws std::invalid_argument
/// when A is non-finite or rank-deficient (no unique nearest rotation).
Matrix3 projectToSO3(const Matrix3& A);

/// Counter-clockwise rotations by `angle` [rad] about the x, y and z axes.
Matrix3 rotX(double angle);
Matrix3 rotY(double angle);
Matrix3 rotZ(double angle);

/// hat(w) v = w × v; vee is its inverse on skew-symmetric matrices.
Matrix3 hat(const Vector3& w);
Vector3 vee(const Matrix3& W);

/// The unique axis–angle form of a rotation: angle in [0, π]; at angle 0 the axis is
/// arbitrary and reported as (1, 0, 0); at angle π the axis is unique up to sign and reported
/// with its first non-zero component positive.
struct AxisAngle {
  Vector3 axis = Vector3::UnitX();  ///< unit vector
  double angle = 0.0;               ///< [rad], in [0, π]
};

/// Angles within this of π [rad] are reported as exactly π, with the canonical axis sign.
inline constexpr double kHalfTurnTolerance = 1e-12;

/// Robust for every angle, including 0 and π (goes through the quaternion; see quaternion.hpp).
AxisAngle axisAngleFromMatrix(const Matrix3& R);

/// Rodrigues' formula. `axis` need not be unit; throws std::invalid_argument if it is zero
/// or non-finite.
Matrix3 matrixFromAxisAngle(const Vector3& axis, double angle);

/// exp: so(3) → SO(3), ω ↦ rotation by |ω| about ω/|ω| (series near 0).
Matrix3 expSO3(const Vector3& omega);

/// log: SO(3) → so(3), the rotation vector with |ω| in [0, π] (at π, the axis sign of
/// axisAngleFromMatrix).
Vector3 logSO3(const Matrix3& R);

/// Z-Y-X (aerospace) angles: R = Rz(yaw) · Ry(pitch) · Rx(roll).
struct YawPitchRoll {
  double yaw = 0.0;    ///< [rad] in (−π, π]
  double pitch = 0.0;  ///< [rad] in [−π/2, π/2]
  double roll = 0.0;   ///< [rad] in (−π, π]
};

Matrix3 matrixFromYpr(const YawPitchRoll& ypr);

/// At gimbal lock (|pitch| = π/2 within 1e-9 of cos) only yaw − roll (pitch = +π/2) or
/// yaw + roll (pitch = −π/2) is determined: roll is reported as 0 and yaw carries the rest.
YawPitchRoll yprFromMatrix(const Matrix3& R);

/// Wraps an angle to (−π, π].
double wrapToPi(double angle);
/// Wraps an angle to [0, 2π).
double wrapToTwoPi(double angle);

}  // namespace quad::geometry
