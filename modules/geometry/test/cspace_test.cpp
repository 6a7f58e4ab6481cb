// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/cspace.hpp"

#include <gtest/gtest.h>

#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

TEST(CSpace, DimensionOfRnTimesSOnIsNTimesNPlusOneOverTwo)
{
  EXPECT_EQ(cspaceDimension(1), 1U);
  EXPECT_EQ(cspaceDimension(2), 3U);   // the car: x, y, θ
  EXPECT_EQ(cspaceDimension(3), 6U);   // the quadcopter: position and attitude
  EXPECT_EQ(cspaceDimension(4), 10U);
  for (int n = 1; n < 10; ++n) {
    EXPECT_EQ(cspaceDimension(n), static_cast<std::size_t>(n + n * (n - 1) / 2));
  }
  EXPECT_THROW(cspaceDimension(0), std::invalid_argument);
}

TEST(CSpace, CarHeadingLivesOnTheCircle)
{
  EXPECT_DOUBLE_EQ(CarConfiguration(0, 0, 2.0 * kPi).theta(), 0.0);
  EXPECT_DOUBLE_EQ(CarConfiguration(0, 0, -0.5).theta(), 2.0 * kPi - 0.5);
  EXPECT_DOUBLE_EQ(CarConfiguration(0, 0, 7.0).theta(), 7.0 - 2.0 * kPi);
  // θ = 0.1 and θ = 2π − 0.1 are 0.2 rad apart, not 2π − 0.2.
  EXPECT_NEAR(carDistance({0, 0, 0.1}, {0, 0, 2.0 * kPi - 0.1}), 0.2, 1e-12);
  EXPECT_NEAR(carDistance({0, 0, 0}, {3, 4, 0}), 5.0, 1e-12);
  EXPECT_NEAR(carDistance({0, 0, 0}, {0, 0, kPi}, 2.0), 2.0 * kPi, 1e-12);
}

TEST(CSpace, CarDistanceIsAMetric)
{
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int i = 0; i < 500; ++i) {
    const CarConfiguration a(u(rng), u(rng), u(rng));
    const CarConfiguration b(u(rng), u(rng), u(rng));
    const CarConfiguration c(u(rng), u(rng), u(rng));
    EXPECT_DOUBLE_EQ(carDistance(a, a), 0.0);
    EXPECT_DOUBLE_EQ(carDistance(a, b), carDistance(b, a));
    EXPECT_LE(carDistance(a, c), carDistance(a, b) + carDistance(b, c) + 1e-12);
  }
}

TEST(CSpace, PosesComposeAndInvert)
{
  const auto qs = uniformRotations(100, test::kSeed);
  for (std::size_t i = 0; i + 1 < qs.size(); i += 2) {
    const Pose3 a{Vector3(1, -2, 3), qs[i]};
    const Pose3 b{Vector3(-0.5, 0.25, 4), qs[i + 1]};
    const Vector3 p(0.3, 0.2, -0.1);
    EXPECT_TRUE(test::near((a * b).transform(p), a.transform(b.transform(p)), 1e-12));
    const Pose3 identity = a * a.inverse();
    EXPECT_TRUE(test::near(identity.p, Vector3::Zero(), 1e-12));
    EXPECT_TRUE(test::sameRotation(identity.q, Quaternion::identity(), 1e-14));
  }
}

}  // namespace
}  // namespace quad::geometry
