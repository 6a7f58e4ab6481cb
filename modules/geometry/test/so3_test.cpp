// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/so3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

using test::near;

TEST(SO3, MembershipNeedsOrthogonalityAndDeterminantOne)
{
  EXPECT_TRUE(isRotation(Matrix3::Identity()));
  EXPECT_TRUE(isRotation(rotZ(0.3) * rotX(-1.2)));
  Eigen::Matrix2d r2;
  r2 << 0, -1, 1, 0;
  EXPECT_TRUE(isRotation(r2));                                      // SO(2)
  EXPECT_FALSE(isRotation(Matrix3(Vector3(1, 1, -1).asDiagonal())));  // reflection: det −1
  EXPECT_FALSE(isRotation(2.0 * Matrix3::Identity()));              // scaling
  EXPECT_FALSE(isRotation(Eigen::MatrixXd::Identity(2, 3)));         // not square
  Matrix3 nan = Matrix3::Identity();
  nan(0, 0) = std::nan("");
  EXPECT_FALSE(isRotation(nan));
  // Tolerance: a rotation perturbed by 1e-7 passes at 1e-6 and fails at 1e-9.
  Matrix3 noisy = rotY(0.4);
  noisy(1, 2) += 1e-7;
  EXPECT_TRUE(isRotation(noisy, 1e-6));
  EXPECT_FALSE(isRotation(noisy, 1e-9));
}

TEST(SO3, ProjectionReturnsTheNearestRotation)
{
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int i = 0; i < 200; ++i) {
    const Matrix3 R = toMatrix(uniformRotation(rng));
    Matrix3 A = R;
    for (int k = 0; k < 9; ++k) {
      A.data()[k] += noise(rng);
    }
    const Matrix3 P = projectToSO3(A);
    EXPECT_TRUE(isRotation(P, 1e-12));
    // Nearest: no worse than the rotation A was made from, nor than random other rotations.
    EXPECT_LE((P - A).norm(), (R - A).norm() + 1e-12);
    EXPECT_LE((P - A).norm(), (toMatrix(uniformRotation(rng)) - A).norm() + 1e-12);
    EXPECT_TRUE(near(projectToSO3(P), P, 1e-12));  // idempotent
  }
  EXPECT_TRUE(near(projectToSO3(Matrix3(Vector3(1, 1, -1).asDiagonal())),
                   Matrix3(Vector3(1, 1, 1).asDiagonal()), 1e-12));
  EXPECT_THROW(projectToSO3(Matrix3::Zero()), std::invalid_argument);
}

TEST(SO3, ElementaryRotationsTurnCounterClockwise)
{
  const double q = kPi / 2.0;
  EXPECT_TRUE(near(rotX(q) * Vector3::UnitY(), Vector3::UnitZ(), 1e-15));
  EXPECT_TRUE(near(rotY(q) * Vector3::UnitZ(), Vector3::UnitX(), 1e-15));
  EXPECT_TRUE(near(rotZ(q) * Vector3::UnitX(), Vector3::UnitY(), 1e-15));
  for (const double a : {-2.0, 0.3, 3.0}) {
    EXPECT_TRUE(near(rotX(a), matrixFromAxisAngle(Vector3::UnitX(), a), 1e-15));
    EXPECT_TRUE(near(rotY(a), matrixFromAxisAngle(Vector3::UnitY(), a), 1e-15));
    EXPECT_TRUE(near(rotZ(a), matrixFromAxisAngle(Vector3::UnitZ(), a), 1e-15));
  }
}

TEST(SO3, AxisAngleRoundTripsInItsUniqueForm)
{
  std::mt19937_64 rng(test::kSeed);
  for (const auto& q : uniformRotations(1000, test::kSeed)) {
    const Matrix3 R = toMatrix(q);
    const AxisAngle aa = axisAngleFromMatrix(R);
    EXPECT_GE(aa.angle, 0.0);
    EXPECT_LE(aa.angle, kPi);
    EXPECT_NEAR(aa.axis.norm(), 1.0, 1e-12);
    EXPECT_TRUE(near(matrixFromAxisAngle(aa.axis, aa.angle), R, 1e-12));
  }
}

TEST(SO3, AxisAngleAtZeroAndPiIsExplicitAndStable)
{
  const AxisAngle zero = axisAngleFromMatrix(Matrix3::Identity());
  EXPECT_EQ(zero.angle, 0.0);
  EXPECT_EQ(zero.axis, Vector3::UnitX());  // arbitrary at 0: documented choice

  // At π the axis is unique up to sign: reported with its first non-zero component positive.
  const std::vector<Vector3> axes = {Vector3(0, 0, 1), Vector3(0, 0, -1), Vector3(1, 2, -2) / 3.0,
                                     Vector3(-1, 2, 2) / 3.0, Vector3(0, -1, 1) / std::sqrt(2.0)};
  for (const Vector3& n : axes) {
    const AxisAngle aa = axisAngleFromMatrix(matrixFromAxisAngle(n, kPi));
    EXPECT_NEAR(aa.angle, kPi, 1e-12);
    const Vector3 expected = n.x() > 0 || (n.x() == 0 && (n.y() > 0 || (n.y() == 0 && n.z() > 0)))
                                 ? n
                                 : Vector3(-n);
    EXPECT_TRUE(near(aa.axis, expected, 1e-12)) << n.transpose();
  }
  // Just below π, the axis is still recovered to full precision.
  const Vector3 n = Vector3(2, -3, 6) / 7.0;
  const AxisAngle aa = axisAngleFromMatrix(matrixFromAxisAngle(n, kPi - 1e-9));
  EXPECT_NEAR(aa.angle, kPi - 1e-9, 1e-12);
  EXPECT_TRUE(near(aa.axis, n, 1e-7));
  // And near 0.
  const AxisAngle small = axisAngleFromMatrix(matrixFromAxisAngle(n, 1e-10));
  EXPECT_NEAR(small.angle, 1e-10, 1e-15);
  EXPECT_TRUE(near(small.axis, n, 1e-6));
}

TEST(SO3, ExpAndLogAreInverse)
{
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    Vector3 w(u(rng), u(rng), u(rng));
    w *= (kPi - 1e-6) * std::abs(u(rng)) / w.norm();  // |w| < π: log recovers w itself
    EXPECT_TRUE(near(logSO3(expSO3(w)), w, 1e-10)) << w.transpose();
    EXPECT_TRUE(isRotation(expSO3(w), 1e-12));
  }
  EXPECT_TRUE(near(expSO3(Vector3(1e-12, 0, 0)), Matrix3::Identity(), 1e-11));
  EXPECT_TRUE(near(hat(Vector3(1, 2, 3)) * Vector3(4, 5, 6), Vector3(1, 2, 3).cross(Vector3(4, 5, 6)), 0));
  EXPECT_TRUE(near(vee(hat(Vector3(1, 2, 3))), Vector3(1, 2, 3), 0));
}

TEST(SO3, YawPitchRollRoundTripsAwayFromGimbalLock)
{
  for (const auto& q : uniformRotations(1000, test::kSeed)) {
    const Matrix3 R = toMatrix(q);
    const YawPitchRoll ypr = yprFromMatrix(R);
    EXPECT_LE(std::abs(ypr.pitch), kPi / 2.0);
    EXPECT_TRUE(near(matrixFromYpr(ypr), R, 1e-9));
  }
  const YawPitchRoll ypr{0.4, -0.7, 1.1};
  const YawPitchRoll back = yprFromMatrix(matrixFromYpr(ypr));
  EXPECT_NEAR(back.yaw, 0.4, 1e-12);
  EXPECT_NEAR(back.pitch, -0.7, 1e-12);
  EXPECT_NEAR(back.roll, 1.1, 1e-12);
}

TEST(SO3, GimbalLockPutsTheFreeAngleInYaw)
{
  for (const double pitch : {kPi / 2.0, -kPi / 2.0}) {
    const Matrix3 R = matrixFromYpr({0.5, pitch, 0.2});
    const YawPitchRoll ypr = yprFromMatrix(R);
    EXPECT_EQ(ypr.pitch, pitch);
    EXPECT_EQ(ypr.roll, 0.0);
    EXPECT_TRUE(near(matrixFromYpr(ypr), R, 1e-12)) << "pitch " << pitch;
  }
}

TEST(SO3, AnglesWrap)
{
  EXPECT_DOUBLE_EQ(wrapToPi(3.0 * kPi / 2.0), -kPi / 2.0);
  EXPECT_DOUBLE_EQ(wrapToPi(-kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapToPi(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapToTwoPi(-0.5), 2.0 * kPi - 0.5);
  EXPECT_DOUBLE_EQ(wrapToTwoPi(2.0 * kPi), 0.0);
  EXPECT_GE(wrapToTwoPi(-1e-18), 0.0);
  EXPECT_LT(wrapToTwoPi(-1e-18), 2.0 * kPi);
}

}  // namespace
}  // namespace quad::geometry
