// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The map's occupied voxels, kept from the mapper's change sets (through a
/// mapping::MapFollower, which fills gaps from snapshots), for a viewer's point cloud: a
/// change costs a hash update, not a snapshot's decoding.

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "quad/geometry/grid.hpp"
#include "quad/mapping/voxel_map.hpp"

namespace quad::display {

class OccupiedVoxels {
public:
  explicit OccupiedVoxels(double resolution) : grid_(resolution) {}

  /// Applies changes in order: a voxel is held while its last change says occupied.
  void apply(const std::vector<mapping::VoxelChange>& changes);
  std::size_t size() const { return keys_.size(); }
  /// Whether anything changed since the last centres().
  bool changed() const { return changed_; }
  /// The centres [m] of the voxels held, in no particular order.
  std::vector<geometry::Vector3> centres();
  double resolution() const { return grid_.resolution(); }

private:
  geometry::VoxelGrid grid_;
  std::unordered_set<std::uint64_t> keys_;
  bool changed_ = false;
};

}  // namespace quad::display
