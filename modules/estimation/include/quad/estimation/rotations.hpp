// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The SO(3) exponential and logarithm the filter is written against: MRPT's Lie group
/// machinery (mrpt::poses::Lie::SO<3>) in the stack, and quad's own Eigen implementation
/// for the benchmark that weighs the two (and for a cross-check).

#include "quad/geometry/so3.hpp"

namespace quad::estimation {

using geometry::Matrix3;
using geometry::Vector3;

/// mrpt::poses::Lie::SO<3>::exp and ::log.
struct MrptRotations {
  static Matrix3 exp(const Vector3& omega);
  static Vector3 log(const Matrix3& R);
};

/// quad::geometry::expSO3 and logSO3 (Rodrigues' formula on Eigen).
struct EigenRotations {
  static Matrix3 exp(const Vector3& omega);
  static Vector3 log(const Matrix3& R);
};

}  // namespace quad::estimation
