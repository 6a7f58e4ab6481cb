// SPDX-License-Identifier: BSD-3-Clause
#include "quad/estimation/rotations.hpp"

#include <mrpt/poses/Lie/SO.h>

#include "quad/geometry/so3.hpp"

namespace quad::estimation {

Matrix3 MrptRotations::exp(const Vector3& omega)
{
  mrpt::poses::Lie::SO<3>::tangent_vector v;
  v[0] = omega.x();
  v[1] = omega.y();
  v[2] = omega.z();
  return mrpt::poses::Lie::SO<3>::exp(v).asEigen();
}

Vector3 MrptRotations::log(const Matrix3& R)
{
  mrpt::poses::Lie::SO<3>::type m;
  m.asEigen() = R;
  const auto v = mrpt::poses::Lie::SO<3>::log(m);
  return {v[0], v[1], v[2]};
}

Matrix3 EigenRotations::exp(const Vector3& omega) { return geometry::expSO3(omega); }

Vector3 EigenRotations::log(const Matrix3& R) { return geometry::logSO3(R); }

}  // namespace quad::estimation
