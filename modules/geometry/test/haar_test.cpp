// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/haar.hpp"

#include <gtest/gtest.h>

#include "quad/geometry/distance.hpp"
#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

constexpr std::size_t kSamples = 20000;
// Kolmogorov–Smirnov critical value at significance 0.01 for large n: 1.628 / √n.
const double kCritical = 1.628 / std::sqrt(static_cast<double>(kSamples));

std::vector<double> angles(const std::vector<Quaternion>& qs)
{
  std::vector<double> out;
  for (const auto& q : qs) {
    out.push_back(geodesicAngle(Quaternion::identity(), q));
  }
  return out;
}

TEST(Haar, RotationAnglesFollowTheHaarDensity)
{
  const double d = kolmogorovSmirnov(angles(uniformRotations(kSamples, test::kSeed)), haarAngleCdf);
  EXPECT_LT(d, kCritical) << "KS statistic " << d;
}

TEST(Haar, LeftAndRightMultiplicationKeepTheDistribution)
{
  const Quaternion g = fromAxisAngle(Vector3(1, -2, 0.5), 2.1);
  std::vector<Quaternion> left;
  std::vector<Quaternion> right;
  for (const auto& q : uniformRotations(kSamples, test::kSeed + 7)) {
    left.push_back(g * q);
    right.push_back(q * g);
  }
  EXPECT_LT(kolmogorovSmirnov(angles(left), haarAngleCdf), kCritical);
  EXPECT_LT(kolmogorovSmirnov(angles(right), haarAngleCdf), kCritical);
  // The rotation axes stay uniform on the sphere: their z component is uniform on [−1, 1].
  std::vector<double> axis_z;
  for (const auto& q : left) {
    axis_z.push_back(axisAngleFromMatrix(toMatrix(q)).axis.z());
  }
  EXPECT_LT(kolmogorovSmirnov(axis_z, [](double z) { return (z + 1.0) / 2.0; }), kCritical);
}

TEST(Haar, UniformEulerAnglesAreNotUniformRotations)
{
  // The test has power: the naive sampler (uniform yaw, pitch, roll) fails it clearly.
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> pitch(-kPi / 2, kPi / 2);
  std::vector<double> naive;
  for (std::size_t i = 0; i < kSamples; ++i) {
    const Matrix3 R = matrixFromYpr({angle(rng), pitch(rng), angle(rng)});
    naive.push_back(axisAngleFromMatrix(R).angle);
  }
  EXPECT_GT(kolmogorovSmirnov(naive, haarAngleCdf), 3.0 * kCritical);
}

TEST(Haar, SamplingIsReproducibleForASeedAndUnitNorm)
{
  const auto a = uniformRotations(100, 42);
  const auto b = uniformRotations(100, 42);
  const auto c = uniformRotations(100, 43);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].vector(), b[i].vector());
    EXPECT_NEAR(a[i].norm(), 1.0, 1e-15);
    EXPECT_GE(a[i].w, 0.0);
  }
  EXPECT_NE(a[0].vector(), c[0].vector());
}

TEST(Haar, AngleDensityIntegratesToOneAndMatchesTheCdf)
{
  double integral = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * kPi / n;
    integral += haarAngleDensity(theta) * kPi / n;
  }
  EXPECT_NEAR(integral, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(haarAngleCdf(0.0), 0.0);
  EXPECT_DOUBLE_EQ(haarAngleCdf(kPi), 1.0);
}

}  // namespace
}  // namespace quad::geometry
