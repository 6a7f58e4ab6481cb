// SPDX-License-Identifier: BSD-3-Clause
// quad::geometry against an independent implementation: MRPT's poses and Lie-group helpers.
#include <gtest/gtest.h>

#include <mrpt/math/CQuaternion.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/Lie/SO.h>

#include "quad/geometry/distance.hpp"
#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

Matrix3 fromMrpt(const mrpt::math::CMatrixDouble33& m)
{
  Matrix3 out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      out(r, c) = m(r, c);
    }
  }
  return out;
}

mrpt::math::CMatrixDouble33 toMrpt(const Matrix3& m)
{
  mrpt::math::CMatrixDouble33 out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      out(r, c) = m(r, c);
    }
  }
  return out;
}

TEST(MrptCrossCheck, QuaternionToMatrixAgrees)
{
  for (const auto& q : uniformRotations(500, test::kSeed)) {
    const mrpt::math::CQuaternionDouble mq(q.w, q.x, q.y, q.z);  // MRPT: (r, x, y, z)
    mrpt::math::CMatrixDouble33 m;
    mq.rotationMatrix(m);
    EXPECT_TRUE(test::near(toMatrix(q), fromMrpt(m), 1e-12));
  }
}

TEST(MrptCrossCheck, ExpAndLogAgree)
{
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int i = 0; i < 500; ++i) {
    const Vector3 w(u(rng), u(rng), u(rng));
    if (w.norm() >= kPi - 1e-3) {
      continue;  // the axis sign at π is a convention
    }
    mrpt::math::CVectorFixedDouble<3> mw;
    mw[0] = w.x();
    mw[1] = w.y();
    mw[2] = w.z();
    const Matrix3 R = fromMrpt(mrpt::poses::Lie::SO<3>::exp(mw));
    EXPECT_TRUE(test::near(expSO3(w), R, 1e-12));
    const auto back = mrpt::poses::Lie::SO<3>::log(toMrpt(R));
    EXPECT_TRUE(test::near(logSO3(R), Vector3(back[0], back[1], back[2]), 1e-9));
  }
}

TEST(MrptCrossCheck, YawPitchRollAgree)
{
  for (const auto& q : uniformRotations(500, test::kSeed + 3)) {
    const YawPitchRoll ypr = yprFromMatrix(toMatrix(q));
    const Matrix3 mrpt_R = fromMrpt(mrpt::poses::Lie::SO<3>::fromYPR(ypr.yaw, ypr.pitch, ypr.roll));
    EXPECT_TRUE(test::near(matrixFromYpr(ypr), mrpt_R, 1e-12));
    const mrpt::poses::CPose3D pose(0, 0, 0, ypr.yaw, ypr.pitch, ypr.roll);
    EXPECT_NEAR(pose.yaw(), ypr.yaw, 1e-9);
    EXPECT_NEAR(pose.pitch(), ypr.pitch, 1e-9);
    EXPECT_NEAR(pose.roll(), ypr.roll, 1e-9);
  }
}

TEST(MrptCrossCheck, RelativeRotationAngleAgrees)
{
  const auto qs = uniformRotations(400, test::kSeed + 5);
  for (std::size_t i = 0; i + 1 < qs.size(); i += 2) {
    const Matrix3 A = toMatrix(qs[i]);
    const Matrix3 B = toMatrix(qs[i + 1]);
    const auto w = mrpt::poses::Lie::SO<3>::log(toMrpt(A.transpose() * B));
    EXPECT_NEAR(geodesicAngle(A, B), std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), 1e-9);
  }
}

}  // namespace
}  // namespace quad::geometry
