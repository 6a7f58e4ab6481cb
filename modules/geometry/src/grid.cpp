// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/grid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace quad::geometry {

namespace {
constexpr int kOctomapMaxValue = 32768;  // OcTree's tree_max_val at depth 16
}

VoxelGrid::VoxelGrid(double resolution) : resolution_(resolution)
{
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("VoxelGrid: resolution " + std::to_string(resolution) +
                                ": must be positive and finite");
  }
}

VoxelIndex VoxelGrid::toIndex(const Vector3& p) const
{
  // floor(p / res), as OctoMap's coordToKey does with its resolution factor 1/res.
  const double factor = 1.0 / resolution_;
  return {static_cast<int>(std::floor(p.x() * factor)), static_cast<int>(std::floor(p.y() * factor)),
          static_cast<int>(std::floor(p.z() * factor))};
}

Vector3 VoxelGrid::centre(const VoxelIndex& i) const
{
  return (i.cast<double>().array() + 0.5).matrix() * resolution_;
}

std::optional<Eigen::Matrix<std::uint16_t, 3, 1>> VoxelGrid::octomapKey(const VoxelIndex& i) const
{
  Eigen::Matrix<std::uint16_t, 3, 1> key;
  for (int a = 0; a < 3; ++a) {
    const int k = i[a] + kOctomapMaxValue;
    if (k < 0 || k >= 2 * kOctomapMaxValue) {
      return std::nullopt;
    }
    key[a] = static_cast<std::uint16_t>(k);
  }
  return key;
}

Lattice::Lattice(const VoxelGrid& grid, const Vector3& min, const Vector3& max) : grid_(grid)
{
  if (!min.allFinite() || !max.allFinite()) {
    throw std::invalid_argument("Lattice: bounds must be finite");
  }
  const double res = grid_.resolution();
  for (int a = 0; a < 3; ++a) {
    // First and last voxel whose centre (i + ½)·res is inside [min, max].
    const auto first = static_cast<int>(std::ceil(min[a] / res - 0.5));
    const auto last = static_cast<int>(std::floor(max[a] / res - 0.5));
    if (last < first) {
      throw std::invalid_argument("Lattice: bounds [" + std::to_string(min[a]) + ", " +
                                  std::to_string(max[a]) + "] on axis " + std::to_string(a) +
                                  " hold no voxel centre at resolution " + std::to_string(res));
    }
    origin_[a] = first;
    dims_[a] = last - first + 1;
  }
}

std::int64_t Lattice::size() const
{
  return static_cast<std::int64_t>(dims_.x()) * dims_.y() * dims_.z();
}

VoxelIndex Lattice::voxel(std::int64_t c) const
{
  if (c < 0 || c >= size()) {
    throw std::out_of_range("Lattice: cell " + std::to_string(c) + " outside [0, " +
                            std::to_string(size()) + ")");
  }
  const std::int64_t nx = dims_.x();
  const std::int64_t nxy = nx * dims_.y();
  return origin_ + VoxelIndex(static_cast<int>(c % nx), static_cast<int>((c % nxy) / nx),
                              static_cast<int>(c / nxy));
}

std::optional<std::int64_t> Lattice::cellAt(const Vector3& p) const
{
  return cell(grid_.toIndex(p));
}

std::int64_t Lattice::nearestCell(const Vector3& p) const
{
  VoxelIndex i = grid_.toIndex(p);
  for (int axis = 0; axis < 3; ++axis) {
    i[axis] = std::clamp(i[axis], origin_[axis], origin_[axis] + dims_[axis] - 1);
  }
  return *cell(i);
}

Vector3 Lattice::centre(std::int64_t c) const { return grid_.centre(voxel(c)); }

}  // namespace quad::geometry
