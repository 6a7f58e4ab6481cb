// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared helpers of the geometry tests: seeded random rotations and matrix comparison.

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

#include "quad/geometry/haar.hpp"
#include "quad/geometry/quaternion.hpp"

namespace quad::geometry::test {

inline constexpr std::uint64_t kSeed = 20240611;

inline ::testing::AssertionResult near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                       double tolerance)
{
  if (a.rows() == b.rows() && a.cols() == b.cols() && (a - b).cwiseAbs().maxCoeff() <= tolerance) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "\n" << a << "\n  differs from\n" << b;
}

/// Same rotation: q and −q are equal rotations.
inline ::testing::AssertionResult sameRotation(const Quaternion& a, const Quaternion& b,
                                               double tolerance)
{
  const double d = std::abs(dot(a.normalized(), b.normalized()));
  if (1.0 - d <= tolerance) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "|a·b| = " << d;
}

}  // namespace quad::geometry::test
