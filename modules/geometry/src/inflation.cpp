// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/inflation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace quad::geometry {

double centreToBoxDistance(const VoxelIndex& offset, double resolution)
{
  // Per axis, the centre is |d|·res from the box's centre and the box reaches ½·res.
  const Eigen::Array3d gap = (offset.cast<double>().array().abs() - 0.5).max(0.0);
  return resolution * gap.matrix().norm();
}

std::vector<VoxelIndex> inflationOffsets(double radius, double resolution)
{
  if (!(radius >= 0.0) || !std::isfinite(radius)) {
    throw std::invalid_argument("inflationOffsets: radius " + std::to_string(radius) +
                                ": must be finite and >= 0");
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("inflationOffsets: resolution " + std::to_string(resolution) +
                                ": must be positive and finite");
  }
  // |d| − ½ ≤ radius/res on every axis bounds the search box.
  // (Rounded up: the distance test below decides; the box only needs to be large enough.)
  const int reach = static_cast<int>(std::ceil(radius / resolution + 0.5));
  std::vector<std::pair<double, VoxelIndex>> found;
  for (int dz = -reach; dz <= reach; ++dz) {
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const VoxelIndex d(dx, dy, dz);
        const double distance = centreToBoxDistance(d, resolution);
        // Ties (a centre exactly at the radius) are blocked whatever the rounding: the
        // conservative side for collisions.
        if (distance <= radius + 1e-9 * resolution) {
          found.emplace_back(distance, d);
        }
      }
    }
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<VoxelIndex> out;
  out.reserve(found.size());
  for (const auto& [distance, d] : found) {
    out.push_back(d);
  }
  return out;
}

}  // namespace quad::geometry
