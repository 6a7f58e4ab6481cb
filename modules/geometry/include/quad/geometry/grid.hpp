// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Maps between the spaces a planner works in (the guide's chapter 3): world coordinates
/// [m] ⇄ voxel indices of the whole world ⇄ cells of a bounded planning lattice.
///
/// Voxel i on an axis covers [i·res, (i+1)·res) and has its centre at (i + ½)·res: the same
/// arithmetic as OctoMap's keys (key = i + 2¹⁵ for its default depth 16), so a voxel here and
/// an octree leaf at the same resolution are the same box. World → voxel is many-to-one
/// (each voxel is a box); restricted to voxel centres, and between voxels and lattice cells,
/// the maps are bijections, which the tests check by round trips.

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "quad/geometry/so3.hpp"

namespace quad::geometry {

using VoxelIndex = Eigen::Vector3i;

/// Hash of a voxel index, for unordered containers of voxels.
struct VoxelIndexHash {
  std::size_t operator()(const VoxelIndex& i) const
  {
    return (static_cast<std::size_t>(static_cast<std::uint32_t>(i.x())) * 73856093U) ^
           (static_cast<std::size_t>(static_cast<std::uint32_t>(i.y())) * 19349663U) ^
           (static_cast<std::size_t>(static_cast<std::uint32_t>(i.z())) * 83492791U);
  }
};

/// The voxel grid of the world at one resolution.
class VoxelGrid {
public:
  /// Throws std::invalid_argument unless resolution > 0 and finite.
  explicit VoxelGrid(double resolution);

  double resolution() const { return resolution_; }
  /// The voxel containing p (boundaries belong to the voxel above).
  VoxelIndex toIndex(const Vector3& p) const;
  /// The centre of voxel i.
  Vector3 centre(const VoxelIndex& i) const;
  /// OctoMap's key of voxel i for a tree of depth 16: i + 32768 on each axis; nothing when the
  /// index is outside the octree's range.
  std::optional<Eigen::Matrix<std::uint16_t, 3, 1>> octomapKey(const VoxelIndex& i) const;

private:
  double resolution_;
};

/// A bounded box of voxels: the planner's lattice. Cells are numbered 0 … size−1 with x
/// fastest, then y, then z.
class Lattice {
public:
  /// The voxels whose centres lie within [min, max] (inclusive) on every axis. Throws
  /// std::invalid_argument when the box is empty, inverted or non-finite.
  Lattice(const VoxelGrid& grid, const Vector3& min, const Vector3& max);

  const VoxelGrid& grid() const { return grid_; }
  const VoxelIndex& origin() const { return origin_; }  ///< voxel index of cell 0
  const Eigen::Vector3i& dims() const { return dims_; }
  std::int64_t size() const;

  bool contains(const VoxelIndex& i) const
  {
    const VoxelIndex d = i - origin_;
    return (d.array() >= 0).all() && (d.array() < dims_.array()).all();
  }
  /// The cell of a voxel, if the voxel is in the lattice. Inline: a planner asks it for every
  /// voxel of an obstacle's inflation as the map changes.
  std::optional<std::int64_t> cell(const VoxelIndex& i) const
  {
    if (!contains(i)) {
      return std::nullopt;
    }
    const VoxelIndex d = i - origin_;
    return d.x() + static_cast<std::int64_t>(dims_.x()) * (d.y() + static_cast<std::int64_t>(dims_.y()) * d.z());
  }
  /// The voxel of a cell; throws std::out_of_range for a cell outside [0, size).
  VoxelIndex voxel(std::int64_t cell) const;
  /// World point → cell, if the point's voxel is in the lattice.
  std::optional<std::int64_t> cellAt(const Vector3& p) const;
  /// The cell nearest p: the cell of p's voxel, each axis clamped into the lattice.
  std::int64_t nearestCell(const Vector3& p) const;
  /// Cell → centre of its voxel [m].
  Vector3 centre(std::int64_t cell) const;

private:
  VoxelGrid grid_;
  VoxelIndex origin_;
  Eigen::Vector3i dims_;
};

}  // namespace quad::geometry
