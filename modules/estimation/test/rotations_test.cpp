// SPDX-License-Identifier: BSD-3-Clause
// MRPT's SO(3) exponential and logarithm against quad's, at fixed seeds and at the edges.
#include "quad/estimation/rotations.hpp"

#include <gtest/gtest.h>

#include <random>

namespace quad::estimation {
namespace {

TEST(Rotations, MrptAndEigenAgreeOnExpAndLogUpToNearlyAHalfTurn)
{
  std::mt19937_64 rng(1);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    Vector3 w(n(rng), n(rng), n(rng));
    w *= (k % 10 == 0 ? 1e-9 : 3.0 * (k % 100) / 100.0) / w.norm();  // 0 (nearly) to 2.97 rad
    const Matrix3 a = MrptRotations::exp(w);
    EXPECT_LT((a - EigenRotations::exp(w)).norm(), 1e-12) << k;
    EXPECT_LT((MrptRotations::log(a) - w).norm(), 1e-9) << k;
    EXPECT_LT((EigenRotations::log(a) - w).norm(), 1e-9) << k;
  }
}

}  // namespace
}  // namespace quad::estimation
