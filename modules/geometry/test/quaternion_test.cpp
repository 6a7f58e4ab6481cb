// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/quaternion.hpp"

#include <gtest/gtest.h>

#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

using test::near;
using test::sameRotation;

const Quaternion kOne{1, 0, 0, 0};
const Quaternion kI{0, 1, 0, 0};
const Quaternion kJ{0, 0, 1, 0};
const Quaternion kK{0, 0, 0, 1};

bool equal(const Quaternion& a, const Quaternion& b)
{
  return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}

TEST(Quaternion, HamiltonProductMatchesTheMultiplicationTable)
{
  // The guide's Table 1, row times column.
  const Quaternion basis[4] = {kOne, kI, kJ, kK};
  const Quaternion table[4][4] = {{kOne, kI, kJ, kK},
                                  {kI, -kOne, kK, -kJ},
                                  {kJ, -kK, -kOne, kI},
                                  {kK, kJ, -kI, -kOne}};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_TRUE(equal(basis[r] * basis[c], table[r][c])) << "row " << r << " column " << c;
    }
  }
  EXPECT_TRUE(equal(kI * kJ * kK, -kOne));  // ijk = −1
}

TEST(Quaternion, MultiplicationMatricesSatisfyQpEqualsLqpEqualsRpq)
{
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> g;
  for (int i = 0; i < 500; ++i) {
    const Quaternion q{g(rng), g(rng), g(rng), g(rng)};
    const Quaternion p{g(rng), g(rng), g(rng), g(rng)};
    const Eigen::Vector4d qp = (q * p).vector();
    EXPECT_TRUE(near(leftMatrix(q) * p.vector(), qp, 1e-12));
    EXPECT_TRUE(near(rightMatrix(p) * q.vector(), qp, 1e-12));
    // For a unit quaternion both are orthogonal, and they commute: (q ⊗ r) ⊗ p = q ⊗ (r ⊗ p).
    const Quaternion u = q.normalized();
    EXPECT_TRUE(near(leftMatrix(u).transpose() * leftMatrix(u), Eigen::Matrix4d::Identity(), 1e-12));
    EXPECT_TRUE(near(leftMatrix(u) * rightMatrix(p), rightMatrix(p) * leftMatrix(u), 1e-12));
  }
}

TEST(Quaternion, MatrixConversionRoundTripsForEveryAngle)
{
  for (const auto& q : uniformRotations(2000, test::kSeed)) {
    const Matrix3 R = toMatrix(q);
    EXPECT_TRUE(isRotation(R, 1e-12));
    EXPECT_TRUE(sameRotation(fromMatrix(R), q, 1e-14));
  }
  // 180° about many axes, where a trace-based conversion divides by ~0.
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> g;
  for (int i = 0; i < 500; ++i) {
    const Vector3 n = Vector3(g(rng), g(rng), g(rng)).normalized();
    const Quaternion q = fromAxisAngle(n, kPi);
    EXPECT_TRUE(sameRotation(fromMatrix(toMatrix(q)), q, 1e-14)) << n.transpose();
  }
}

TEST(Quaternion, RotationBySandwichEqualsTheMatrix)
{
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> g;
  for (const auto& q : uniformRotations(200, test::kSeed)) {
    const Vector3 v(g(rng), g(rng), g(rng));
    const Quaternion sandwich = q * Quaternion{0, v.x(), v.y(), v.z()} * q.conjugate();
    EXPECT_NEAR(sandwich.w, 0.0, 1e-12);
    EXPECT_TRUE(near(sandwich.imaginary(), toMatrix(q) * v, 1e-12));
    EXPECT_TRUE(near(toMatrix(-q), toMatrix(q), 1e-15));  // q and −q: one rotation
  }
}

TEST(Quaternion, ProductComposesRotations)
{
  const auto qs = uniformRotations(400, test::kSeed);
  for (std::size_t i = 0; i + 1 < qs.size(); i += 2) {
    EXPECT_TRUE(near(toMatrix(qs[i] * qs[i + 1]), toMatrix(qs[i]) * toMatrix(qs[i + 1]), 1e-12));
  }
}

TEST(Quaternion, InverseConjugateNormAndCanonicalSign)
{
  const Quaternion q{1, -2, 3, -4};
  EXPECT_DOUBLE_EQ(q.norm(), std::sqrt(30.0));
  const Quaternion id = q * q.inverse();
  EXPECT_NEAR(id.w, 1.0, 1e-15);
  EXPECT_NEAR(id.imaginary().norm(), 0.0, 1e-15);
  EXPECT_TRUE(equal(q.conjugate(), Quaternion{1, 2, -3, 4}));
  EXPECT_NEAR(q.normalized().norm(), 1.0, 1e-15);
  EXPECT_THROW(Quaternion({0, 0, 0, 0}).normalized(), std::invalid_argument);
  EXPECT_THROW(Quaternion({0, 0, 0, 0}).inverse(), std::invalid_argument);
  EXPECT_TRUE(equal(Quaternion({-0.5, 0.5, 0.5, 0.5}).canonical(), {0.5, -0.5, -0.5, -0.5}));
  EXPECT_TRUE(equal(Quaternion({0, -1, 0, 0}).canonical(), {0, 1, 0, 0}));
  EXPECT_TRUE(equal(Quaternion({0, 0, -1, 0}).canonical(), {0, 0, 1, 0}));
}

TEST(Quaternion, SlerpFollowsTheShorterArcAtConstantSpeed)
{
  const Quaternion a = fromAxisAngle(Vector3::UnitZ(), 0.2);
  const Quaternion b = fromAxisAngle(Vector3::UnitZ(), 1.4);
  EXPECT_TRUE(sameRotation(slerp(a, b, 0.0), a, 1e-15));
  EXPECT_TRUE(sameRotation(slerp(a, b, 1.0), b, 1e-15));
  for (const double t : {0.25, 0.5, 0.75}) {
    EXPECT_TRUE(sameRotation(slerp(a, b, t), fromAxisAngle(Vector3::UnitZ(), 0.2 + 1.2 * t), 1e-14));
  }
  // −b is b: still the 1.2 rad arc, not the long way round.
  EXPECT_TRUE(sameRotation(slerp(a, -b, 0.5), fromAxisAngle(Vector3::UnitZ(), 0.8), 1e-14));
  // Nearly equal inputs do not divide by ~0.
  const Quaternion c = fromAxisAngle(Vector3::UnitX(), 1e-13);
  const Quaternion mid = slerp(Quaternion::identity(), c, 0.5);
  EXPECT_NEAR(mid.norm(), 1.0, 1e-15);
}

TEST(Quaternion, AxisAngleConstructionIsHalfAngled)
{
  const Quaternion q = fromAxisAngle(Vector3(0, 0, 2), kPi / 2.0);  // axis normalized
  EXPECT_NEAR(q.w, std::cos(kPi / 4.0), 1e-15);
  EXPECT_NEAR(q.z, std::sin(kPi / 4.0), 1e-15);
  EXPECT_THROW(fromAxisAngle(Vector3::Zero(), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace quad::geometry
