// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Where a ray crosses an axis-aligned box: the slab test (Kay & Kajiya 1986), shared by the
/// obstacles' boxes and the voxel maps' extent.

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "quad/geometry/so3.hpp"

namespace quad::world {

/// The span [t_in, t_out] of t in [0, t_max] with origin + t·direction inside the box
/// [lo, hi]; nothing when the ray misses it. A direction parallel to a slab keeps the ray in
/// it or out of it whole.
inline std::optional<std::pair<double, double>> rayBoxSpan(const geometry::Vector3& o, const geometry::Vector3& d,
                                                           const geometry::Vector3& lo, const geometry::Vector3& hi,
                                                           double t_max)
{
  double t0 = 0.0;
  double t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      if (o[a] < lo[a] || o[a] > hi[a]) {
        return std::nullopt;
      }
      continue;
    }
    double near = (lo[a] - o[a]) / d[a];
    double far = (hi[a] - o[a]) / d[a];
    if (near > far) {
      std::swap(near, far);
    }
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) {
      return std::nullopt;
    }
  }
  return std::pair(t0, t1);
}

}  // namespace quad::world
