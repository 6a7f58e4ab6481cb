// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/so3.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "quad/geometry/quaternion.hpp"

namespace quad::geometry {

bool isRotation(const Eigen::MatrixXd& A, double tolerance)
{
  if (A.rows() != A.cols() || A.rows() == 0 || !A.allFinite()) {
    return false;
  }
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(A.rows(), A.cols());
  const double orthogonality = (A.transpose() * A - identity).cwiseAbs().maxCoeff();
  return orthogonality <= tolerance && std::abs(A.determinant() - 1.0) <= tolerance;
}

Matrix3 projectToSO3(const Matrix3& A)
{
  if (!A.allFinite()) {
    throw std::invalid_argument("projectToSO3: matrix has non-finite entries");
  }
  const Eigen::JacobiSVD<Matrix3> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vector3 s = svd.singularValues();
  // The nearest rotation is unique only when at most the smallest singular value vanishes
  // and the two smallest are distinct when det(A) < 0; refuse the rank-deficient case.
  if (s[1] <= 1e-12 * std::max(1.0, s[0])) {
    throw std::invalid_argument("projectToSO3: matrix is rank-deficient, no unique nearest rotation");
  }
  Matrix3 U = svd.matrixU();
  const Matrix3 V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) {
    U.col(2) *= -1.0;  // flip the direction of the smallest singular value
  }
  return U * V.transpose();
}

Matrix3 rotX(double angle)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Matrix3 R;
  R << 1, 0, 0, 0, c, -s, 0, s, c;
  return R;
}

Matrix3 rotY(double angle)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Matrix3 R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}

Matrix3 rotZ(double angle)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Matrix3 R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

Matrix3 hat(const Vector3& w)
{
  Matrix3 W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

Vector3 vee(const Matrix3& W) { return {W(2, 1), W(0, 2), W(1, 0)}; }

AxisAngle axisAngleFromMatrix(const Matrix3& R)
{
  // Through the canonical quaternion (w >= 0): angle = 2 atan2(|v|, w) is accurate at every
  // angle, where acos((tr R − 1)/2) loses half the digits near 0 and π.
  Quaternion q = fromMatrix(R);
  AxisAngle out;
  if (q.w <= kHalfTurnTolerance / 2.0) {
    // A half turn, up to rounding (a matrix built for π carries sin π ≈ 1e-16): the axis is
    // unique only up to sign, so report exactly π with the canonical sign, rather than let
    // rounding noise in w pick it.
    q.w = 0.0;
    q = q.canonical();
    out.angle = kPi;
    out.axis = q.imaginary().normalized();
    return out;
  }
  const Vector3 v = q.imaginary();
  const double s = v.norm();
  out.angle = 2.0 * std::atan2(s, q.w);
  if (s > 0.0) {
    out.axis = v / s;
  }
  return out;
}

Matrix3 matrixFromAxisAngle(const Vector3& axis, double angle)
{
  const double n = axis.norm();
  if (!(n > 0.0) || !std::isfinite(n) || !std::isfinite(angle)) {
    throw std::invalid_argument("matrixFromAxisAngle: axis must be non-zero and finite, angle finite");
  }
  const Vector3 u = axis / n;
  const Matrix3 K = hat(u);
  return Matrix3::Identity() + std::sin(angle) * K + (1.0 - std::cos(angle)) * K * K;
}

Matrix3 expSO3(const Vector3& omega)
{
  const double theta = omega.norm();
  const Matrix3 W = hat(omega);
  if (theta < 1e-8) {
    // Taylor: sin θ/θ ≈ 1 − θ²/6, (1 − cos θ)/θ² ≈ 1/2 − θ²/24; error below 1e-33 here.
    return Matrix3::Identity() + (1.0 - theta * theta / 6.0) * W +
           (0.5 - theta * theta / 24.0) * W * W;
  }
  return Matrix3::Identity() + (std::sin(theta) / theta) * W +
         ((1.0 - std::cos(theta)) / (theta * theta)) * W * W;
}

Vector3 logSO3(const Matrix3& R)
{
  const AxisAngle aa = axisAngleFromMatrix(R);
  return aa.axis * aa.angle;
}

Matrix3 matrixFromYpr(const YawPitchRoll& ypr)
{
  return rotZ(ypr.yaw) * rotY(ypr.pitch) * rotX(ypr.roll);
}

YawPitchRoll yprFromMatrix(const Matrix3& R)
{
  YawPitchRoll out;
  // R(2,0) = −sin(pitch); clamp against rounding just outside [−1, 1].
  out.pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double cos_pitch = std::hypot(R(0, 0), R(1, 0));
  if (cos_pitch > 1e-9) {
    out.yaw = std::atan2(R(1, 0), R(0, 0));
    out.roll = std::atan2(R(2, 1), R(2, 2));
  } else {
    // Gimbal lock: R(0,1) = −sin(yaw ∓ roll), R(1,1) = cos(yaw ∓ roll); put it all in yaw.
    out.pitch = R(2, 0) < 0.0 ? kPi / 2.0 : -kPi / 2.0;
    out.yaw = std::atan2(-R(0, 1), R(1, 1));
    out.roll = 0.0;
  }
  out.yaw = wrapToPi(out.yaw);
  out.roll = wrapToPi(out.roll);
  return out;
}

double wrapToPi(double angle)
{
  double a = std::fmod(angle, 2.0 * kPi);  // (−2π, 2π)
  if (a <= -kPi) {
    a += 2.0 * kPi;
  } else if (a > kPi) {
    a -= 2.0 * kPi;
  }
  return a;
}

double wrapToTwoPi(double angle)
{
  double a = std::fmod(angle, 2.0 * kPi);
  if (a < 0.0) {
    a += 2.0 * kPi;
  }
  // fmod of a tiny negative number plus 2π can round to exactly 2π.
  return a >= 2.0 * kPi ? 0.0 : a;
}

}  // namespace quad::geometry
