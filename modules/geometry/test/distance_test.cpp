// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/distance.hpp"

#include <gtest/gtest.h>

#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

TEST(Distance, RhoIsHalfTheRotationAngleAndFrobeniusIsTwoRootTwoSinOfHalfOfIt)
{
  const auto qs = uniformRotations(2000, test::kSeed);
  for (std::size_t i = 0; i + 1 < qs.size(); i += 2) {
    const Quaternion& a = qs[i];
    const Quaternion& b = qs[i + 1];
    const double theta = geodesicAngle(toMatrix(a), toMatrix(b));
    EXPECT_NEAR(rho(a, b), theta / 2.0, 1e-9);
    EXPECT_NEAR(geodesicAngle(a, b), theta, 1e-9);
    EXPECT_NEAR(frobeniusDistance(toMatrix(a), toMatrix(b)), 2.0 * std::sqrt(2.0) * std::sin(theta / 2.0),
                1e-12);
    // ρ_s depends on the representative, ρ does not.
    EXPECT_NEAR(rhoS(a, b) + rhoS(a, -b), kPi, 1e-9);
    EXPECT_DOUBLE_EQ(rho(a, b), rho(a, -b));
    EXPECT_DOUBLE_EQ(rho(a, b), rho(-a, b));
  }
}

TEST(Distance, RotationMetricsSatisfyTheMetricAxioms)
{
  const auto qs = uniformRotations(1500, test::kSeed + 1);
  using Metric = std::function<double(const Quaternion&, const Quaternion&)>;
  const std::vector<std::pair<const char*, Metric>> metrics = {
      {"rho", [](const Quaternion& a, const Quaternion& b) { return rho(a, b); }},
      {"geodesic", [](const Quaternion& a, const Quaternion& b) { return geodesicAngle(a, b); }},
      {"frobenius",
       [](const Quaternion& a, const Quaternion& b) { return frobeniusDistance(toMatrix(a), toMatrix(b)); }},
  };
  for (const auto& [name, d] : metrics) {
    for (std::size_t i = 0; i + 2 < qs.size(); i += 3) {
      const Quaternion &a = qs[i], &b = qs[i + 1], &c = qs[i + 2];
      EXPECT_NEAR(d(a, a), 0.0, 1e-7) << name;
      EXPECT_NEAR(d(a, -a), 0.0, 1e-7) << name;  // same rotation
      EXPECT_GT(d(a, b), 0.0) << name;
      EXPECT_DOUBLE_EQ(d(a, b), d(b, a)) << name;
      EXPECT_LE(d(a, c), d(a, b) + d(b, c) + 1e-12) << name;
      // Bi-invariance: d(g a, g b) = d(a, b) = d(a g, b g).
      EXPECT_NEAR(d(c * a, c * b), d(a, b), 1e-9) << name;
      EXPECT_NEAR(d(a * c, b * c), d(a, b), 1e-9) << name;
    }
  }
}

TEST(Distance, YawPitchRollDistanceWrapsAndIsAMetricOnAngleTriples)
{
  EXPECT_NEAR(yprDistance({kPi - 0.01, 0, 0}, {-kPi + 0.01, 0, 0}), 0.02, 1e-12);
  EXPECT_NEAR(yprDistance({0.1, 0.2, 0.3}, {0.4, 0.6, 0.3}), 0.5, 1e-12);
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> pitch(-kPi / 2, kPi / 2);
  for (int i = 0; i < 500; ++i) {
    const YawPitchRoll a{angle(rng), pitch(rng), angle(rng)};
    const YawPitchRoll b{angle(rng), pitch(rng), angle(rng)};
    const YawPitchRoll c{angle(rng), pitch(rng), angle(rng)};
    EXPECT_DOUBLE_EQ(yprDistance(a, a), 0.0);
    EXPECT_DOUBLE_EQ(yprDistance(a, b), yprDistance(b, a));
    EXPECT_LE(yprDistance(a, c), yprDistance(a, b) + yprDistance(b, c) + 1e-12);
  }
}

TEST(Distance, YawPitchRollDistanceIsNotARotationMetricAtGimbalLock)
{
  // Two angle triples of the same rotation (pitch 90°: only yaw − roll matters) are far apart.
  const YawPitchRoll a{0.5, kPi / 2.0, 0.2};
  const YawPitchRoll b{0.3, kPi / 2.0, 0.0};
  EXPECT_NEAR(geodesicAngle(matrixFromYpr(a), matrixFromYpr(b)), 0.0, 1e-7);
  EXPECT_GT(yprDistance(a, b), 0.28);
}

TEST(Distance, GeodesicAngleIsAccurateNearZeroAndPi)
{
  const Vector3 n = Vector3(1, 2, 2) / 3.0;
  EXPECT_NEAR(geodesicAngle(Matrix3::Identity(), matrixFromAxisAngle(n, 1e-9)), 1e-9, 1e-17);
  EXPECT_NEAR(geodesicAngle(Matrix3::Identity(), matrixFromAxisAngle(n, kPi - 1e-9)), kPi - 1e-9, 1e-12);
  EXPECT_NEAR(geodesicAngle(Quaternion::identity(), fromAxisAngle(n, 1e-9)), 1e-9, 1e-20);
}

}  // namespace
}  // namespace quad::geometry
