// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A solid voxel map in the world: the occupied voxels of a real scan (an OctoMap or a point
/// cloud), kept as one bit per voxel over the box they fill, so that a depth ray is marched
/// voxel by voxel (Amanatides & Woo 1987) and a contact looks only at the voxels around the
/// vehicle: what a query costs does not grow with the size of the map.
///
/// Voxels are those of geometry::VoxelGrid: voxel i covers [i·res, (i+1)·res) on each axis,
/// OctoMap's own boxes at the same resolution.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quad/geometry/grid.hpp"

namespace quad::world {

using geometry::Vector3;
using geometry::VoxelIndex;

class VoxelMap {
public:
  /// The largest box of voxels a map may span (one bit each: 128 MiB).
  static constexpr std::int64_t kMaxCells = std::int64_t{1} << 30;

  /// The occupied voxels of `grid` (duplicates allowed). Throws std::invalid_argument when
  /// there are none, or when the box they span holds more than kMaxCells voxels (a finer
  /// resolution than the map can afford; the message gives the count).
  VoxelMap(std::string name, const geometry::VoxelGrid& grid, std::vector<VoxelIndex> occupied);

  /// Where the map came from (its file), for messages.
  const std::string& name() const { return name_; }
  double resolution() const { return grid_.resolution(); }
  const geometry::VoxelGrid& grid() const { return grid_; }
  /// Every occupied voxel once, sorted by z, then y, then x.
  const std::vector<VoxelIndex>& occupiedVoxels() const { return occupied_; }
  bool occupied(const VoxelIndex& i) const;
  /// The box [m] the occupied voxels fill.
  void bounds(Vector3& lo, Vector3& hi) const;

  /// Smallest t in [0, t_max] with origin + t·direction in an occupied voxel (direction unit);
  /// 0 when the origin is in one.
  std::optional<double> raycast(const Vector3& origin, const Vector3& direction, double t_max) const;

  /// Distance [m] from p to the nearest occupied voxel's box (0 inside one), when it is at
  /// most `cap`; searched in growing shells of voxels around p, so it costs what is near.
  /// Voxels whose tops lie at or below `above` [m] do not count (what the vehicle stands on).
  std::optional<double> distance(const Vector3& p, double cap, double above = -kFar) const;

  /// The highest top [m] of an occupied voxel at or below `z_max` [m] in the columns within
  /// `reach` [m] of p horizontally, if any is above `floor` [m].
  std::optional<double> topBelow(const Vector3& p, double reach, double z_max, double floor) const;

  static constexpr double kFar = 1e9;  ///< [m] below anything

private:
  bool inBox(const VoxelIndex& i) const;
  /// The lowest voxel layer whose tops lie above z [m].
  int firstLayerAbove(double z) const;
  std::int64_t cellOf(const VoxelIndex& i) const;

  std::string name_;
  geometry::VoxelGrid grid_;
  VoxelIndex origin_;          // the box's first voxel
  Eigen::Vector3i dims_;       // voxels along x, y, z
  std::vector<std::uint64_t> bits_;
  std::vector<VoxelIndex> occupied_;
};

}  // namespace quad::world
