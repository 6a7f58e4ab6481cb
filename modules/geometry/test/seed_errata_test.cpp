// SPDX-License-Identifier: BSD-3-Clause
// The guide's worked examples, computed from first principles: the ones it gets right, and
// its errata (docs/seed-errata.md lists each with the test here that shows it).
#include <gtest/gtest.h>

#include <cmath>

#include "quad/geometry/cspace.hpp"
#include "quad/geometry/distance.hpp"
#include "test_rotations.hpp"

namespace quad::geometry {
namespace {

using test::near;
using test::sameRotation;

const double kHalfRoot2 = std::sqrt(0.5);

Matrix3 matrix(std::initializer_list<double> rows)
{
  Matrix3 m;
  auto it = rows.begin();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      m(r, c) = *it++;
    }
  }
  return m;
}

Eigen::Matrix4d matrix4(std::initializer_list<double> rows)
{
  Eigen::Matrix4d m;
  auto it = rows.begin();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      m(r, c) = *it++;
    }
  }
  return m;
}

// ---- What the guide gets right ----

TEST(SeedExamples, DimensionOfCIsThreeForAPlanarBodyAndSixForASpatialOne)
{
  EXPECT_EQ(cspaceDimension(2), 3U);
  EXPECT_EQ(cspaceDimension(3), 6U);
}

TEST(SeedExamples, RzOfHalfPiSendsXToYAndFixesZ)
{
  // Eq. (3) and the example after it.
  const Matrix3 R = rotZ(kPi / 2.0);
  EXPECT_TRUE(near(R, matrix({0, -1, 0, 1, 0, 0, 0, 0, 1}), 1e-15));
  EXPECT_TRUE(near(R * Vector3(1, 0, 0), Vector3(0, 1, 0), 1e-15));
  EXPECT_TRUE(near(R * Vector3(0, 0, 1), Vector3(0, 0, 1), 1e-15));
}

TEST(SeedExamples, RxAndRzOfEquation2AreCounterClockwise)
{
  for (const double a : {0.3, 1.0, 2.5}) {
    const double c = std::cos(a), s = std::sin(a);
    EXPECT_TRUE(near(rotX(a), matrix({1, 0, 0, 0, c, -s, 0, s, c}), 1e-15));
    EXPECT_TRUE(near(rotZ(a), matrix({c, -s, 0, s, c, 0, 0, 0, 1}), 1e-15));
  }
}

TEST(SeedExamples, Table2RotationMatricesAreRightForTheNormalizedQuaternions)
{
  const std::vector<std::pair<Quaternion, Matrix3>> rows = {
      {{1, 0, 0, 0}, Matrix3::Identity()},
      {{0, 1, 0, 0}, matrix({1, 0, 0, 0, -1, 0, 0, 0, -1})},
      {{0, 0, 1, 0}, matrix({-1, 0, 0, 0, 1, 0, 0, 0, -1})},
      {{0, 0, 0, 1}, matrix({-1, 0, 0, 0, -1, 0, 0, 0, 1})},
      {{1, 1, 0, 0}, matrix({1, 0, 0, 0, 0, -1, 0, 1, 0})},
      {{1, 0, 1, 0}, matrix({0, 0, 1, 0, 1, 0, -1, 0, 0})},
      {{1, 0, 0, 1}, matrix({0, -1, 0, 1, 0, 0, 0, 0, 1})},
  };
  for (const auto& [q, R] : rows) {
    EXPECT_TRUE(near(toMatrix(q), R, 1e-15)) << q.vector().transpose();
  }
}

TEST(SeedExamples, Equation6IsHalfTheRotationAngle)
{
  const Quaternion a = fromAxisAngle(Vector3(1, 1, 0), 0.4);
  const Quaternion b = fromAxisAngle(Vector3(0, 1, 1), 2.0);
  EXPECT_NEAR(rho(a, b), geodesicAngle(a, b) / 2.0, 1e-12);
}

TEST(SeedExamples, GuideFourByFourMatrixSplitsIntoItsABCDParts)
{
  // The guide's decomposition of its 4×4 matrix into a·A + b·B + c·C + d·D is consistent.
  const double a = 0.3, b = -1.2, c = 0.7, d = 2.0;
  const Eigen::Matrix4d lhs = matrix4({a, b, c, d, b, -a, d, -c, c, -d, -a, b, d, c, -b, -a});
  const Eigen::Matrix4d A = Eigen::Vector4d(1, -1, -1, -1).asDiagonal();
  const Eigen::Matrix4d B = matrix4({0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0});
  const Eigen::Matrix4d C = matrix4({0, 0, 1, 0, 0, 0, 0, -1, 1, 0, 0, 0, 0, 1, 0, 0});
  const Eigen::Matrix4d D = matrix4({0, 0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, 1, 0, 0, 0});
  EXPECT_TRUE(near(lhs, a * A + b * B + c * C + d * D, 1e-15));
}

// ---- Errata ----

TEST(SeedErrata, NInRnTimesSOnIsTheSpaceDimensionNotTheDegreesOfFreedom)
{
  // A rigid body in R³ (n = 3) has 6 degrees of freedom, the dimension of C.
  EXPECT_EQ(cspaceDimension(3), 6U);
  EXPECT_NE(cspaceDimension(3), 3U);
}

TEST(SeedErrata, RyInEquation2TurnsClockwise)
{
  // Eq. (2) prints Ry(φ) = [[cos, 0, −sin], [0, 1, 0], [sin, 0, cos]]: that is Ry(−φ).
  const auto guide_ry = [](double a) {
    return matrix({std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a)});
  };
  for (const double a : {0.3, 1.0, 2.5}) {
    EXPECT_TRUE(near(guide_ry(a), rotY(-a), 1e-15));
    EXPECT_FALSE(near(guide_ry(a), rotY(a), 1e-3));
  }
  // Counter-clockwise about y sends z to x; the guide's matrix sends it to −x.
  EXPECT_TRUE(near(rotY(kPi / 2) * Vector3::UnitZ(), Vector3::UnitX(), 1e-15));
  EXPECT_TRUE(near(guide_ry(kPi / 2) * Vector3::UnitZ(), -Vector3::UnitX(), 1e-15));
  // And Table 2's own 90° rotation about y (quaternion (1, 0, 1, 0)) is the correct Ry.
  EXPECT_TRUE(near(toMatrix({1, 0, 1, 0}), rotY(kPi / 2), 1e-15));
}

TEST(SeedErrata, GuideFourByFourMatrixMultipliesByTheConjugate)
{
  // The guide's matrix M(q) = [[a,b,c,d],[b,−a,d,−c],[c,−d,−a,b],[d,c,−b,−a]] computes
  // q ⊗ p*, not q ⊗ p: M(q) = L(q)·diag(1, −1, −1, −1). For q = 1 it is not the identity.
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> g;
  for (int i = 0; i < 100; ++i) {
    const Quaternion q{g(rng), g(rng), g(rng), g(rng)};
    const Quaternion p{g(rng), g(rng), g(rng), g(rng)};
    const Eigen::Matrix4d M = matrix4({q.w, q.x, q.y, q.z, q.x, -q.w, q.z, -q.y, q.y, -q.z,
                                       -q.w, q.x, q.z, q.y, -q.x, -q.w});
    EXPECT_TRUE(near(M * p.vector(), (q * p.conjugate()).vector(), 1e-12));
    EXPECT_FALSE(near(M * p.vector(), (q * p).vector(), 1e-6));
  }
}

TEST(SeedErrata, Table2FourByFourMatricesAreRightMultiplicationByTheConjugate)
{
  // Table 2's "quaternion 4×4" matrices equal R(q*) (p ↦ p ⊗ q*), neither L(q) (p ↦ q ⊗ p)
  // nor the guide's own 4×4 formula.
  const std::vector<std::pair<Quaternion, Eigen::Matrix4d>> rows = {
      {{0, 1, 0, 0}, matrix4({0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0})},
      {{0, 0, 1, 0}, matrix4({0, 0, 1, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, -1, 0, 0})},
      {{0, 0, 0, 1}, matrix4({0, 0, 0, 1, 0, 0, -1, 0, 0, 1, 0, 0, -1, 0, 0, 0})},
      {{1, 1, 0, 0}, matrix4({1, 1, 0, 0, -1, 1, 0, 0, 0, 0, 1, -1, 0, 0, 1, 1})},
      {{1, 0, 1, 0}, matrix4({1, 0, 1, 0, 0, 1, 0, 1, -1, 0, 1, 0, 0, -1, 0, 1})},
      {{1, 0, 0, 1}, matrix4({1, 0, 0, 1, 0, 1, -1, 0, 0, 1, 1, 0, -1, 0, 0, 1})},
  };
  for (const auto& [q, table] : rows) {
    const Eigen::Matrix4d guide_formula = leftMatrix(q) * Eigen::Vector4d(1, -1, -1, -1).asDiagonal();
    EXPECT_TRUE(near(table, rightMatrix(q.conjugate()), 0)) << q.vector().transpose();
    EXPECT_FALSE(near(table, leftMatrix(q), 1e-9)) << q.vector().transpose();
    EXPECT_FALSE(near(table, guide_formula, 1e-9)) << q.vector().transpose();
  }
  // For q = 1 the table's identity is right, and the guide's formula gives diag(1, −1, −1, −1).
  EXPECT_TRUE(near(leftMatrix(Quaternion::identity()), Eigen::Matrix4d::Identity(), 0));
}

TEST(SeedErrata, QuaternionKIsAHalfTurnAboutZNotX)
{
  const AxisAngle aa = axisAngleFromMatrix(toMatrix({0, 0, 0, 1}));
  EXPECT_NEAR(aa.angle, kPi, 1e-15);
  EXPECT_TRUE(near(aa.axis, Vector3::UnitZ(), 1e-15));
}

TEST(SeedErrata, QuarterTurnsAboutXAndYMoveTheYZAndZXPlanes)
{
  // About x, x is fixed and y → z: the y–z plane turns (the guide says x–z).
  const Matrix3 Rx = toMatrix({1, 1, 0, 0});
  EXPECT_TRUE(near(Rx * Vector3::UnitX(), Vector3::UnitX(), 1e-15));
  EXPECT_TRUE(near(Rx * Vector3::UnitY(), Vector3::UnitZ(), 1e-15));
  // About y, y is fixed and z → x: the z–x plane turns (the guide says y–z).
  const Matrix3 Ry = toMatrix({1, 0, 1, 0});
  EXPECT_TRUE(near(Ry * Vector3::UnitY(), Vector3::UnitY(), 1e-15));
  EXPECT_TRUE(near(Ry * Vector3::UnitZ(), Vector3::UnitX(), 1e-15));
}

TEST(SeedErrata, AQuaternionOfNormRootTwoScalesByTwoItDoesNotEncodeTheAngle)
{
  // q v q* with |q| = √2 stretches v by |q|² = 2; the rotation is that of q/|q|.
  const Quaternion q{1, 1, 0, 0};
  const Quaternion v{0, 0, 1, 0};
  const Quaternion image = q * v * q.conjugate();
  EXPECT_TRUE(near(image.imaginary(), Vector3(0, 0, 2), 1e-15));
  const Quaternion u = q.normalized();
  EXPECT_TRUE(near((u * v * u.conjugate()).imaginary(), Vector3(0, 0, 1), 1e-15));
  EXPECT_NEAR(axisAngleFromMatrix(toMatrix(q)).angle, kPi / 2.0, 1e-15);
}

TEST(SeedErrata, Equation4IsScalarLastWhileTheRestIsScalarFirst)
{
  // 90° about z by eq. (4): (x s, y s, z s, c) = (0, 0, √½, √½). Read as the guide's
  // (a, b, c, d) (scalar first), those numbers are a different rotation: 180° about (0, 1, 1)/√2.
  const Eigen::Vector4d eq4(0, 0, kHalfRoot2, kHalfRoot2);
  const Quaternion scalar_last{eq4[3], eq4[0], eq4[1], eq4[2]};
  const Quaternion read_as_abcd = Quaternion::fromVector(eq4);
  EXPECT_TRUE(near(toMatrix(scalar_last), rotZ(kPi / 2), 1e-15));
  const AxisAngle wrong = axisAngleFromMatrix(toMatrix(read_as_abcd));
  EXPECT_NEAR(wrong.angle, kPi, 1e-12);
  EXPECT_TRUE(near(wrong.axis, Vector3(0, kHalfRoot2, kHalfRoot2), 1e-12));
}

TEST(SeedErrata, UnitQuaternionsCoverRotationsTwiceNotOnce)
{
  const Quaternion q = fromAxisAngle(Vector3(1, 2, 3), 0.7);
  EXPECT_NE(q.vector(), (-q).vector());
  EXPECT_TRUE(near(toMatrix(q), toMatrix(-q), 1e-15));
}

TEST(SeedErrata, DistanceExampleQuaternionsAndResult)
{
  // Eq. (7): R1 is 90° about x and R2 is −90° about z.
  const Matrix3 R1 = matrix({1, 0, 0, 0, 0, -1, 0, 1, 0});
  const Matrix3 R2 = matrix({0, 1, 0, -1, 0, 0, 0, 0, 1});
  EXPECT_TRUE(near(R1, rotX(kPi / 2), 1e-15));
  EXPECT_TRUE(near(R2, rotZ(-kPi / 2), 1e-15));
  // Eq. (8) takes h1 = (1, 0, 0, 0) (the identity) and h2 = (0, 1, 0, −1) (norm √2).
  // Their quaternions are:
  const Quaternion h1 = fromMatrix(R1);
  const Quaternion h2 = fromMatrix(R2);
  EXPECT_TRUE(near(h1.vector(), Eigen::Vector4d(kHalfRoot2, kHalfRoot2, 0, 0), 1e-15));
  EXPECT_TRUE(near(h2.vector(), Eigen::Vector4d(kHalfRoot2, 0, 0, -kHalfRoot2), 1e-15));
  EXPECT_NEAR(Quaternion({0, 1, 0, -1}).norm(), std::sqrt(2.0), 1e-15);
  // Eqs. (9), (13), (14): π/3, 2π/3 and ρ = π/3 (the guide has π/2 for all three).
  EXPECT_NEAR(rhoS(h1, h2), kPi / 3.0, 1e-12);
  EXPECT_NEAR(rhoS(h1, -h2), 2.0 * kPi / 3.0, 1e-12);
  EXPECT_NEAR(rho(h1, h2), kPi / 3.0, 1e-12);
  // The rotations are 120° apart (the guide concludes 180°).
  EXPECT_NEAR(geodesicAngle(R1, R2), 2.0 * kPi / 3.0, 1e-12);
  EXPECT_NEAR(frobeniusDistance(R1, R2), std::sqrt(6.0), 1e-12);  // 2√2 sin 60°
}

TEST(SeedErrata, NegatingAMatrixIsNotTheQuaternionSignFlip)
{
  // Eq. (11) forms −R2 entrywise: det(−R) = −1, a reflection, not a rotation. The sign
  // ambiguity is of the quaternion: h and −h give the same R.
  const Matrix3 R2 = rotZ(-kPi / 2);
  EXPECT_FALSE(isRotation(-R2));
  EXPECT_NEAR((-R2).determinant(), -1.0, 1e-15);
  EXPECT_TRUE(near(toMatrix(-fromMatrix(R2)), R2, 1e-15));
}

TEST(SeedErrata, YawPitchRollDifferencesMustBeWrapped)
{
  // Eq. (15) as printed puts yaw 179° and −179° 358° apart; they are 2° apart.
  const double deg = kPi / 180.0;
  const YawPitchRoll a{179 * deg, 0, 0};
  const YawPitchRoll b{-179 * deg, 0, 0};
  EXPECT_NEAR(std::abs(a.yaw - b.yaw), 358 * deg, 1e-12);
  EXPECT_NEAR(yprDistance(a, b), 2 * deg, 1e-12);
  EXPECT_NEAR(geodesicAngle(matrixFromYpr(a), matrixFromYpr(b)), 2 * deg, 1e-12);
}

TEST(SeedErrata, CarCSpaceIsRTwoTimesTheCircleNotASubsetOfRThree)
{
  // With θ ∈ [0, 2π) as an interval, θ = 0.01 and θ = 2π − 0.01 are 2π − 0.02 apart; on S¹
  // they are 0.02 apart: the headings are nearly the same.
  const CarConfiguration a(0, 0, 0.01);
  const CarConfiguration b(0, 0, 2.0 * kPi - 0.01);
  EXPECT_NEAR(std::abs(a.theta() - b.theta()), 2.0 * kPi - 0.02, 1e-12);
  EXPECT_NEAR(carDistance(a, b), 0.02, 1e-12);
}

/// Number of connected pieces of a finely sampled interval after removing one point: a
/// finite model of the cut-point arguments of the guide's topology examples.
int piecesAfterRemoving(double lo, bool lo_closed, double hi, bool hi_closed, double removed)
{
  const int n = 1000;
  std::vector<double> points;
  for (int k = 0; k <= n; ++k) {
    const double x = lo + (hi - lo) * k / n;
    if ((k == 0 && !lo_closed) || (k == n && !hi_closed) || std::abs(x - removed) < 1e-12) {
      continue;
    }
    points.push_back(x);
  }
  int pieces = points.empty() ? 0 : 1;
  for (std::size_t i = 1; i < points.size(); ++i) {
    pieces += points[i] - points[i - 1] > 1.5 * (hi - lo) / n ? 1 : 0;
  }
  return pieces;
}

TEST(SeedErrata, RemovingAnInteriorPointDisconnectsTheOpenIntervalToo)
{
  // The guide: removing a point from (0, 1) does not disconnect it. It does, like [0, 1].
  EXPECT_EQ(piecesAfterRemoving(0, false, 1, false, 0.5), 2);
  EXPECT_EQ(piecesAfterRemoving(0, true, 1, true, 0.5), 2);
  // The true difference: [0, 1] has points whose removal keeps it connected (its ends).
  EXPECT_EQ(piecesAfterRemoving(0, true, 1, true, 0.0), 1);
}

TEST(SeedErrata, RemovingAnEndpointLeavesASegmentConnected)
{
  // The guide: removing a point from a line segment disconnects it. Only an interior point
  // does; removing any point of a circle never does, which is why they differ.
  EXPECT_EQ(piecesAfterRemoving(0, true, 1, true, 1.0), 1);
  EXPECT_EQ(piecesAfterRemoving(0, true, 1, true, 0.3), 2);
}

}  // namespace
}  // namespace quad::geometry
